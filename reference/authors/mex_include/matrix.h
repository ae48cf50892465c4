/* MATLAB's MEX API ships a "matrix.h" beside "mex.h"; Octave declares the same functions in
 * "mex.h" alone. The release's sources include both, so this stand-in forwards to Octave's. */
#ifndef PHDSLAM_AUTHORS_MATRIX_H
#define PHDSLAM_AUTHORS_MATRIX_H
#include "mex.h"
#endif
