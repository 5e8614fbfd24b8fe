/* Wrong step 9: the sampler is right, the pdf forgets the h in its numerator (dtheta/dt =
   h / (h^2 + (t - delta)^2)). Caught by step9.pdf_integral and step9.pdf_at_samples. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf)
{
    float t = fogrt_sample_equiangular(delta, h, a, b, u, pdf);
    *pdf /= h;
    return t;
}
float cw_equiangular_pdf(float delta, float h, float a, float b, float t)
{
    return fogrt_equiangular_pdf(delta, h, a, b, t) / h;
}
