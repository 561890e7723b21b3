/* The single translation unit of the test binary that compiles wrinkle's implementations. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"
