/* Step 9 (bonus): equiangular sampling toward a point light.

   Light scattered toward the camera from a point light falls off as 1/r^2 along the ray;
   sampling t uniformly in the angle the segment subtends at the light cancels it. The light
   is at distance h from the ray's line, closest at t = delta (coursework.h).

   Convention: t = a at u = 0, rising with u (coursework.h).

   Check it:  make check-step STEP=9           (pictures in build/coursework/step9_*.png)  */
#include <math.h>
#include "coursework.h"

float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf)
{
    /* TODO: t in [a, b] with density proportional to 1 / (h^2 + (t - delta)^2) */
    (void)delta; (void)h; (void)b; (void)u;
    *pdf = 1.0f;
    return a;
}

float cw_equiangular_pdf(float delta, float h, float a, float b, float t)
{
    /* TODO: the same density at any t (0 outside [a, b]) */
    (void)delta; (void)h; (void)a; (void)b; (void)t;
    return 0.0f;
}
