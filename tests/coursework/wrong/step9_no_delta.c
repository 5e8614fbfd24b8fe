/* Wrong step 9: the angles measured from t = 0 instead of the closest approach t = delta.
   Caught by step9.chi2 ("crowd around t = 0 instead of ... delta"). */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf)
{
    double ta = atan2(a, h), tb = b < INFINITY ? atan2(b, h) : 1.5707963267948966, t;
    (void)delta;
    t = h * tan(ta + u * (tb - ta));
    if (t < a) t = a;
    if (t > b) t = b;
    *pdf = (float)(h / ((tb - ta) * (h * h + t * t)));
    return (float)t;
}
float cw_equiangular_pdf(float delta, float h, float a, float b, float t)
{
    double ta = atan2(a, h), tb = b < INFINITY ? atan2(b, h) : 1.5707963267948966;
    (void)delta;
    if (t < a || t > b) return 0.0f;
    return (float)(h / ((tb - ta) * ((double)h * h + (double)t * t)));
}
