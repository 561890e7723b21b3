// The one C++ translation unit that compiles wrinkle's implementation (the stb/sokol one-TU rule).
// Every other file (main.cpp here) includes the same headers without WRINKLE_IMPLEMENTATION.
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"
