/* Wrong step 2: the estimator scores the flights that collide before d, so its mean is
   1 - T. Caught by step2.estimator. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_transmittance(float sigma_t, float distance)
{
    return (sigma_t > 0.0f && distance > 0.0f) ? expf(-sigma_t * distance) : 1.0f;
}
float cw_transmittance_estimate(float sigma_t, float distance, float u)
{
    return -log1pf(-u) / sigma_t < distance ? 1.0f : 0.0f;
}
