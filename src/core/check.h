#pragma once
// Internal invariants as checks that print their operands (pbrt-v4's CHECK_EQ): a failed check is a bug in
// radwalk, never bad input, so it throws InternalError (exit code 4) with the expression, both values and the
// source line. Use InputError for what a user can fix and NumericalError for what the numbers refuse.
//
//   RADWALK_CHECK(cond)            cond is true
//   RADWALK_CHECK_EQ(a, b)         a == b        (likewise _NE, _LT, _LE, _GT, _GE)
//   RADWALK_DCHECK(cond), RADWALK_DCHECK_EQ(a, b), ...: the same in debug builds; nothing (not even the
//   evaluation of the operands) with NDEBUG, for checks in hot loops.
#include <sstream>
#include <string>

#include "core/error.h"

namespace radwalk::detail {

// The path of a source file from the repository root (src/..., apps/..., tests/...), for messages.
std::string source_path(const char* file);

// "FILE:LINE: check failed: EXPR (A OP B with a = .., b = ..)" as an InternalError.
template <class A, class B>
[[noreturn]] void fail_check(const char* file, int line, const char* expression, const A& a, const B& b) {
  std::ostringstream s;
  s.precision(17);
  s << source_path(file) << ':' << line << ": check failed: " << expression << " (left " << a << ", right " << b << ')';
  throw InternalError(s.str());
}
[[noreturn]] void fail_check(const char* file, int line, const char* expression);

template <class Op, class A, class B>
void check_op(Op op, const A& a, const B& b, const char* file, int line, const char* expression) {
  if (!op(a, b)) [[unlikely]]
    fail_check(file, line, expression, a, b);
}

}  // namespace radwalk::detail

#define RADWALK_CHECK(cond) \
  ((cond) ? static_cast<void>(0) : ::radwalk::detail::fail_check(__FILE__, __LINE__, #cond))

// An expression (usable where a statement is not), each operand evaluated once.
#define RADWALK_CHECK_OP(a, op, b)                                                                  \
  ::radwalk::detail::check_op([](const auto& x, const auto& y) { return bool(x op y); }, (a), (b), __FILE__, \
                              __LINE__, #a " " #op " " #b)

#define RADWALK_CHECK_EQ(a, b) RADWALK_CHECK_OP(a, ==, b)
#define RADWALK_CHECK_NE(a, b) RADWALK_CHECK_OP(a, !=, b)
#define RADWALK_CHECK_LT(a, b) RADWALK_CHECK_OP(a, <, b)
#define RADWALK_CHECK_LE(a, b) RADWALK_CHECK_OP(a, <=, b)
#define RADWALK_CHECK_GT(a, b) RADWALK_CHECK_OP(a, >, b)
#define RADWALK_CHECK_GE(a, b) RADWALK_CHECK_OP(a, >=, b)

#ifdef NDEBUG
#define RADWALK_DCHECK(cond) static_cast<void>(0)
#define RADWALK_DCHECK_OP(a, op, b) static_cast<void>(0)
#else
#define RADWALK_DCHECK(cond) RADWALK_CHECK(cond)
#define RADWALK_DCHECK_OP(a, op, b) RADWALK_CHECK_OP(a, op, b)
#endif
#define RADWALK_DCHECK_EQ(a, b) RADWALK_DCHECK_OP(a, ==, b)
#define RADWALK_DCHECK_LT(a, b) RADWALK_DCHECK_OP(a, <, b)
#define RADWALK_DCHECK_LE(a, b) RADWALK_DCHECK_OP(a, <=, b)
