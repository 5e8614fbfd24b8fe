/* Reference solution of step 9 (docs/coursework.md): fogrt's equiangular sampler. */
#include "../coursework.h"

float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf)
{
    return fogrt_sample_equiangular(delta, h, a, b, u, pdf);
}
float cw_equiangular_pdf(float delta, float h, float a, float b, float t)
{
    return fogrt_equiangular_pdf(delta, h, a, b, t);
}
