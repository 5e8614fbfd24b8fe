/* Step 1: free-flight distance sampling (paper section 3.1, eq. 4-6).

   A ray travelling through homogeneous fog meets a fog particle after a random distance t.
   Collisions form a Poisson process of rate sigma_t (the paper's lambda), so the chance of
   travelling t without a collision is eq. 4 and the CDF of the first collision is eq. 6.
   Write the sampler (invert eq. 6 for a uniform u in [0, 1)) and its density.

   Check it:  make check-step STEP=1           (pictures in build/coursework/step1_*.png)
   Rules: u can be exactly 0 but never 1; sigma_t ranges from 1e-6 to 1e6; every answer
   must be finite. See docs/coursework.md for what each check means.                      */
#include <math.h>
#include "coursework.h"

float cw_sample_free_flight(float sigma_t, float u)
{
    /* TODO: return the distance t with P(distance <= t) = u under eq. 6 */
    (void)sigma_t; (void)u;
    return 0.0f;
}

float cw_free_flight_pdf(float sigma_t, float t)
{
    /* TODO: the density of the distances your sampler returns (0 for t < 0) */
    (void)sigma_t; (void)t;
    return 0.0f;
}
