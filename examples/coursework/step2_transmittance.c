/* Step 2: transmittance (paper section 3.2, eq. 7-8).

   Light losing a fraction sigma_t dt of itself over every stretch dt (eq. 7) keeps the
   fraction of eq. 8 after a distance d. Write eq. 8, and an estimate of the same number
   from ONE free-flight sample drawn with u: its average over many u must equal eq. 8.
   (Your step 1 sampler, or fogrt_sample_exponential, gives the free flight.)

   Check it:  make check-step STEP=2           (pictures in build/coursework/step2_*.png)
   Rules: sigma_t = 0 is clear air; distance may be +infinity; answers stay finite.      */
#include <math.h>
#include "coursework.h"

float cw_transmittance(float sigma_t, float distance)
{
    /* TODO: eq. 8 */
    (void)sigma_t; (void)distance;
    return 0.5f;
}

float cw_transmittance_estimate(float sigma_t, float distance, float u)
{
    /* TODO: one free flight from u; score it so that the mean score is eq. 8 */
    (void)sigma_t; (void)distance; (void)u;
    return 0.5f;
}
