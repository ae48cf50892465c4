/* Force-included (-include) into every MEX source of the authors' release when it is built for
 * GNU Octave. Octave's mxDuplicateArray returns an array whose numeric data is shared with the
 * argument (copy-on-write at the Octave level, but MEX code writes through raw pointers), so a MEX
 * function that duplicates its input and edits the copy in place also edits the caller's variable,
 * and an mxRealloc of the shared buffer frees memory the caller still owns. This header replaces
 * mxDuplicateArray by a copy that allocates fresh storage for every numeric, logical, char, cell
 * and struct array, recursively. */
#ifndef PHDSLAM_AUTHORS_DEEP_DUPLICATE_H
#define PHDSLAM_AUTHORS_DEEP_DUPLICATE_H

#include <stddef.h>
#include <string.h>

#include "mex.h"

static mxArray* phdslam_deep_duplicate(const mxArray* in) {
  if (in == NULL) return NULL;
  const mwSize ndim = mxGetNumberOfDimensions(in);
  const mwSize* dims = mxGetDimensions(in);
  const size_t count = mxGetNumberOfElements(in);
  if (mxIsStruct(in)) {
    const int nfields = mxGetNumberOfFields(in);
    const char** names =
        (const char**)mxMalloc((size_t)(nfields > 0 ? nfields : 1) * sizeof(char*));
    for (int f = 0; f < nfields; ++f) names[f] = mxGetFieldNameByNumber(in, f);
    mxArray* out = mxCreateStructArray(ndim, dims, nfields, names);
    mxFree((void*)names);
    for (size_t i = 0; i < count; ++i) {
      for (int f = 0; f < nfields; ++f) {
        const mxArray* field = mxGetFieldByNumber(in, (mwIndex)i, f);
        if (field != NULL) mxSetFieldByNumber(out, (mwIndex)i, f, phdslam_deep_duplicate(field));
      }
    }
    return out;
  }
  if (mxIsCell(in)) {
    mxArray* out = mxCreateCellArray(ndim, dims);
    for (size_t i = 0; i < count; ++i) {
      const mxArray* cell = mxGetCell(in, (mwIndex)i);
      if (cell != NULL) mxSetCell(out, (mwIndex)i, phdslam_deep_duplicate(cell));
    }
    return out;
  }
  if (mxIsNumeric(in) || mxIsLogical(in) || mxIsChar(in)) {
    mxArray* out = NULL;
    if (mxIsLogical(in)) {
      out = mxCreateLogicalArray(ndim, dims);
    } else if (mxIsChar(in)) {
      out = mxCreateCharArray(ndim, dims);
    } else {
      out =
          mxCreateNumericArray(ndim, dims, mxGetClassID(in), mxIsComplex(in) ? mxCOMPLEX : mxREAL);
    }
    const size_t bytes = count * mxGetElementSize(in) * (mxIsComplex(in) ? 2 : 1);
    if (bytes > 0) memcpy(mxGetData(out), mxGetData(in), bytes);
    return out;
  }
  /* Anything else (function handles, objects) is not used by the release's MEX inputs. */
  return mxDuplicateArray(in);
}

#define mxDuplicateArray(a) phdslam_deep_duplicate(a)

#endif
