/* Step 3: the Henyey-Greenstein phase function (paper section 3.3, eq. 9-12).

   At a fog collision the light continues in a new direction wi. Its angle theta to the
   propagation direction d = -wo follows HG (eq. 9) with asymmetry g (g > 0: mostly
   forward); eq. 10-11 sample mu = cos(theta) by inverting the CDF, eq. 12 the azimuth.
   Write eq. 9, the mu sampler, and the full direction (build an orthonormal frame around
   d, then wi = sin(theta) cos(phi) x + sin(theta) sin(phi) y + cos(theta) d).

   Check it:  make check-step STEP=3           (pictures in build/coursework/step3_*.png)
   Rules: -1 < g < 1, g = 0 exactly included; u in [0, 1); mu rises with u (mu = -1 at
   u = 0), the direction in which the paper writes eq. 11.                                 */
#include <math.h>
#include "coursework.h"

float cw_hg_phase(float g, float mu)
{
    /* TODO: eq. 9, per steradian */
    (void)g; (void)mu;
    return 0.0f;
}

float cw_sample_hg_mu(float g, float u)
{
    /* TODO: eq. 11 (what happens at g = 0?) */
    (void)g; (void)u;
    return 0.0f;
}

fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2)
{
    /* TODO: a unit direction around d = -wo: mu from u1, phi from u2 (eq. 12) */
    (void)g; (void)u1; (void)u2;
    return wo;
}
