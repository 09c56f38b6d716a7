#pragma once
// Numbers as messages and text files write them: one helper instead of a local one per file, so that every
// message writes a double the same way for the same precision and notation.
#include <string>

#include "core/types.h"

namespace radwalk {

// printf's three notations of a double: %g, %e, %f.
enum class NumberNotation { general, scientific, fixed };

// x as printf writes it with conversion %.{precision}g (general), %.{precision}e (scientific) or
// %.{precision}f (fixed): precision is the number of significant digits for general (0 counts as 1), of
// digits after the point for the other two. General with precision p is also what an ostream writes at
// precision(p) with the default floatfield (the C++ standard defines the ostream's output by that
// conversion), so a text once written through an ostringstream reads the same. Non-finite values read "inf",
// "-inf", "nan" as printf writes them. Precision is clamped to [0, 40]. Never throws except std::bad_alloc.
std::string format_number(double x, int precision = 6, NumberNotation notation = NumberNotation::general);

// "(r, g, b)": each channel by format_number(c[k], precision) (general notation).
std::string format_rgb(const Rgb& c, int precision = 6);

}  // namespace radwalk
