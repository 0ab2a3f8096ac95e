#pragma once
/// \file eigen_no_malloc.hpp
/// Force-included (-include) into the translation units of the no-allocation
/// test, including its own copy of numeric/src/collision/collision.cpp: Eigen checks
/// every heap allocation against set_is_malloc_allowed(), and any failed
/// eigen_assert (a forbidden allocation, or an index out of range) is
/// recorded instead of aborting or being compiled out by NDEBUG.
#define EIGEN_RUNTIME_NO_MALLOC

namespace superball::testing {
void eigen_assertion_failed(const char* what, const char* file, int line);
}

#define eigen_assert(x)                                                          \
  do {                                                                           \
    if (!static_cast<bool>(x)) ::superball::testing::eigen_assertion_failed(#x, __FILE__, __LINE__); \
  } while (false)
