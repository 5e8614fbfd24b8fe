/* Wrong step 2: T = 1 - sigma_t d, eq. 8's first-order expansion, clamped at 0. Caught by
   step2.eq8. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_transmittance(float sigma_t, float distance)
{
    float t = 1.0f - sigma_t * distance;
    return t > 0.0f ? t : 0.0f;
}
float cw_transmittance_estimate(float sigma_t, float distance, float u)
{
    return -log1pf(-u) / sigma_t >= distance ? 1.0f : 0.0f;
}
