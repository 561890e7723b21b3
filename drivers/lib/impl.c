/* The one translation unit that compiles wrinkle's implementation for every driver, validation
 * driver and benchmark (they link this object; none of them defines WRINKLE_IMPLEMENTATION). */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"
