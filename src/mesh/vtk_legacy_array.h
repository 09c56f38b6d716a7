#pragma once
// One array of a legacy VTK file (.vtk): the values after a section header (POINTS n TYPE, SCALARS NAME TYPE k,
// a FIELD array NAME k n TYPE, OFFSETS TYPE, ...), in the file's encoding, as VTK's legacy writer stores them:
//   ASCII:  numbers separated by white space, anywhere after the header's last word; strings one a line after the
//           header's line, each byte that is not printable (and '%') written as %XX (two hex digits);
//   BINARY: after the header's line, the values back to back, big-endian, of the type's size (char 1, short 2,
//           int 4, long 8, vtkIdType 4 (VTK writes it as int), vtktypeint64 8, float 4, double 8; bit arrays
//           packed 8 to a byte, the first in the high bit); strings each after a length word whose top 2 bits
//           say its size (11: 1 byte, 10: 2, 01: 4, 00: 8; the other bits the length, big-endian).
// A variant array is pairs "TYPE TEXT" in both encodings. After the values VTK's writer may add a METADATA block
// (COMPONENT_NAMES and INFORMATION lines up to a blank line): it is skipped.
//
// Bounded where read: the values a header declares (tuples x components) must fit the bytes left (BINARY: their
// size each; ASCII: at least 2 bytes each but the last), before anything is allocated; an ASCII value must be a
// whole token that is a number (a whole number in its type's range for the integer types), a string's length at
// most the bytes left. Values are kept only when asked (the arrays radwalk uses), else checked and skipped.
// Type names are VTK's, exactly, in any case (VTK matches a prefix: "floatx" was float; here it is refused).
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/vtk_legacy_scan.h"

namespace radwalk {

struct LegacyArray {
  std::string type;                  // the type's name, lower case
  bool numeric = true;               // false for string and variant arrays
  bool integer = false;              // an integer (or bit) type
  std::vector<double> numbers;       // when kept and numeric: tuples x components values
  std::vector<std::string> strings;  // when kept and a string array
};

// Reads the array whose type is the token `type` at the scan position: `tuples` x `components` values (both >= 0),
// then a METADATA block if one follows. `what` names it in refusals ("POINTS", "FIELD array 'rho'", ...).
LegacyArray read_legacy_array(LegacyScanner& scan, const LegacyScanner::Token& type, std::int64_t tuples,
                              std::int64_t components, bool binary, bool keep, const std::string& what);

// Whether `name` (any case) is one of the legacy format's type names.
bool is_legacy_type(std::string_view name);

// A count or size in a header: a whole number from `least` to `most`, else refused naming `what`.
std::int64_t read_legacy_count(LegacyScanner& scan, const std::string& what, std::int64_t least, std::int64_t most);

// VTK's decoding of names and ASCII strings: %XX (two hex digits) is the byte XX; everything else is itself.
std::string decode_legacy_string(std::string_view text);

}  // namespace radwalk
