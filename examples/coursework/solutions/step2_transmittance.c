/* Reference solution of step 2 (docs/coursework.md): fogrt's Beer-Lambert transmittance,
   and the estimator that scores a free flight which reaches the end of the segment. */
#include "../coursework.h"

float cw_transmittance(float sigma_t, float distance) { return fogrt_transmittance(sigma_t, distance); }

/* P(free flight >= d) = exp(-sigma_t d) (eq. 4): the indicator is an unbiased estimate. */
float cw_transmittance_estimate(float sigma_t, float distance, float u)
{
    return fogrt_sample_exponential(sigma_t, u) >= distance ? 1.0f : 0.0f;
}
