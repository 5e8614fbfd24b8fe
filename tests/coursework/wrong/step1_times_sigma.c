/* Wrong step 1: multiplies by sigma_t where eq. 6's inverse divides (the mean free path
   1/sigma_t taken for sigma_t). Caught by step1.chi2. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_sample_free_flight(float sigma_t, float u) { return -logf(1.0f - u) * sigma_t; }
float cw_free_flight_pdf(float sigma_t, float t) { return t < 0.0f ? 0.0f : sigma_t * expf(-sigma_t * t); }
