/* Wrong step 1: -log(u) instead of -log(1 - u). The distribution is right (1 - u is as
   uniform as u), so the histogram passes; it is not eq. 6's inverse, and u = 0 gives an
   infinite distance. Caught by step1.inverse_cdf and step1.edges. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_sample_free_flight(float sigma_t, float u) { return -logf(u) / sigma_t; }
float cw_free_flight_pdf(float sigma_t, float t) { return t < 0.0f ? 0.0f : sigma_t * expf(-sigma_t * t); }
