#pragma once
// The values of one array of a VTK XML file (mesh/vtp_xml.h), decoded as VTK stores them:
//   ascii:    numbers separated by white space (a String array: each string's byte values, then 0);
//   binary:   base64 text of [header][data], inline in the element;
//   appended: the same [header][data] at the array's offset in the appended bytes, raw or base64 (the offset
//             counts bytes of the raw data, or characters of the base64 text).
// The header is words of header_type (UInt32 or UInt64) in the file's byte order. Uncompressed it is one word,
// the data's byte count. With vtkZLibDataCompressor it is [n, B, r, c_0 ... c_{n-1}]: n blocks of B bytes each,
// the last of r bytes when r > 0, block k compressed by zlib into c_k bytes, the blocks back to back after the
// header. The base64 of the header and of the data may be two texts (each padded) or one: decoding 4 characters
// at a time gives the same bytes for both.
//
// Every bound is checked before anything is allocated or read: the header's words against the bytes present, the
// data's size against the values the array must hold (its tuples x components, or the count its place gives:
// a piece's points, cells), each block's declared size against zlib's largest ratio (1032:1) times its compressed
// size, and inflation is stopped at the declared size (more is refused: a zip bomb), fewer bytes too. Values are
// swapped from BigEndian where the file says so. A refusal is one InputError naming the file, the XML line of the
// array's start tag, the array and what is wrong.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/vtp_xml.h"

namespace radwalk {

inline constexpr double kZlibLargestRatio = 1032;  // zlib (deflate) never compresses better than 1032:1

// The numbers of a numeric array, as doubles (Int64 and UInt64 above 2^53 rounded). `expected` is the number of
// values it must hold (tuples x components), or -1 for any multiple of its components (and its NumberOfTuples
// times its components when it declares them). Every value is finite unless the type is Float32 or Float64.
std::vector<double> decode_numbers(const std::string& path, const VtpDocument& doc, const VtpArray& array,
                                   std::int64_t expected);

// The strings of a String array: NUL-terminated in binary data, 0-terminated byte values in ascii. As many as its
// NumberOfTuples x NumberOfComponents when it declares tuples (more or fewer is refused).
std::vector<std::string> decode_strings(const std::string& path, const VtpDocument& doc, const VtpArray& array);

// "DataArray 'NAME'" (or "Array 'NAME'", without the name when it has none): how messages name an array.
std::string array_label(const VtpArray& array);

}  // namespace radwalk
