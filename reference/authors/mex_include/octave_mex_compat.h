/* Force-included into the release's C++ MEX sources when they are built for GNU Octave 7: names of
 * MATLAB's MEX API that Octave's mex.h lacks and that the release's argument validation mentions
 * (class IDs for objects, typed accessors of complex integer arrays). The release's functions
 * never receive such arrays; these definitions only let the sources compile. */
#ifndef PHDSLAM_AUTHORS_OCTAVE_MEX_COMPAT_H
#define PHDSLAM_AUTHORS_OCTAVE_MEX_COMPAT_H

#include "mex.h"

#define mxOPAQUE_CLASS ((mxClassID)(mxFUNCTION_CLASS + 1))
#define mxOBJECT_CLASS ((mxClassID)(mxFUNCTION_CLASS + 2))

#define PHDSLAM_COMPLEX_ACCESSOR(Name, Type) \
  static inline Type* Name(const mxArray* a) { return (Type*)mxGetData(a); }
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexInt8s, mxComplexInt8)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexUint8s, mxComplexUint8)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexInt16s, mxComplexInt16)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexUint16s, mxComplexUint16)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexInt32s, mxComplexInt32)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexUint32s, mxComplexUint32)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexInt64s, mxComplexInt64)
PHDSLAM_COMPLEX_ACCESSOR(mxGetComplexUint64s, mxComplexUint64)
#undef PHDSLAM_COMPLEX_ACCESSOR

#endif
