/* Wrong step 1: the pdf without the factor sigma_t in front (exp(-sigma_t t) is eq. 4, the
   probability of no collision, not a density). Caught by step1.pdf_integral. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_sample_free_flight(float sigma_t, float u) { return -log1pf(-u) / sigma_t; }
float cw_free_flight_pdf(float sigma_t, float t) { return t < 0.0f ? 0.0f : expf(-sigma_t * t); }
