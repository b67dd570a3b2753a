/*
 * mathconst.h - <math.h> with M_PI, also where the C library keeps it
 * behind a feature macro (strict ISO C); not part of the API.
 */
#ifndef MPB_MATHCONST_H
#define MPB_MATHCONST_H

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#endif /* MPB_MATHCONST_H */
