/* Reference solution of step 1 (docs/coursework.md): fogrt's own free-flight sampler and
   its density behind the kit's signatures. Try the step yourself before reading this. */
#include "../coursework.h"

float cw_sample_free_flight(float sigma_t, float u) { return fogrt_sample_exponential(sigma_t, u); }
float cw_free_flight_pdf(float sigma_t, float t) { return fogrt_exponential_pdf(sigma_t, t); }
