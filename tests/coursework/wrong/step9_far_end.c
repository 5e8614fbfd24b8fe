/* Wrong on purpose (tests/test_coursework.c): equiangular sampling from the far end of the
   segment, t(u) = t(1 - u). The distribution is right; the kit's convention is t = a at
   u = 0, and step9.edges says that the convention is what failed. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf)
{
    double ta = atan2((double)a - delta, h), tb = isinf(b) ? 1.5707963267948966 : atan2((double)b - delta, h);
    double th = tb - (double)u * (tb - ta), t = delta + h * tan(th);
    if (t < a) t = a;
    if (t > b) t = b;
    *pdf = (float)(h / ((tb - ta) * (h * (double)h + (t - delta) * (t - delta))));
    return (float)t;
}
float cw_equiangular_pdf(float delta, float h, float a, float b, float t)
{
    double ta = atan2((double)a - delta, h), tb = isinf(b) ? 1.5707963267948966 : atan2((double)b - delta, h);
    if (t < a || t > b) return 0.0f;
    return (float)(h / ((tb - ta) * (h * (double)h + ((double)t - delta) * ((double)t - delta))));
}
