/* Wrong step 3: phi = pi xi2, half of eq. 12's circle. Caught by step3.direction_chi2
   ("azimuth sectors ... empty"). */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_hg_phase(float g, float mu) { return fogrt_hg_phase(g, mu); }
float cw_sample_hg_mu(float g, float u) { return fogrt_sample_hg_mu(g, u); }
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2)
{
    float mu = fogrt_sample_hg_mu(g, u1), s = sqrtf(fmaxf(0.0f, 1.0f - mu * mu)), phi = 3.14159265f * u2;
    float dx = -wo.x, dy = -wo.y, dz = -wo.z, ax, ay, az, len, bx, by, bz;
    fogrt_vec3 w;
    /* a frame around d: a = normalize(d x e) with e the axis least aligned with d, b = d x a */
    if (fabsf(dx) < 0.6f) { ax = 0.0f; ay = dz; az = -dy; } else { ax = -dz; ay = 0.0f; az = dx; }
    len = sqrtf(ax * ax + ay * ay + az * az);
    ax /= len; ay /= len; az /= len;
    bx = dy * az - dz * ay; by = dz * ax - dx * az; bz = dx * ay - dy * ax;
    w.x = s * cosf(phi) * ax + s * sinf(phi) * bx + mu * dx;
    w.y = s * cosf(phi) * ay + s * sinf(phi) * by + mu * dy;
    w.z = s * cosf(phi) * az + s * sinf(phi) * bz + mu * dz;
    return w;
}
