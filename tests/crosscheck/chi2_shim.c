/* tests/crosscheck/chi2_shim.c - fogrt's samplers as a shared library for chi2_mitsuba.py.
   Each function works on n directions at once (arrays of floats, xyz interleaved), so the
   Python side hands Mitsuba's chi-square harness whole batches. */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"

static fogrt_vec3 v3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
static void put(float *out, int i, fogrt_vec3 w) { out[3 * i] = w.x; out[3 * i + 1] = w.y; out[3 * i + 2] = w.z; }
static fogrt_vec3 get(const float *in, int i) { return v3(in[3 * i], in[3 * i + 1], in[3 * i + 2]); }

/* The footprint of kind 5: tests/footprint_case.h's spot over a floor, with the sphere the
   build puts around its lit patch (fogrt__footprint_bound). */
#include "../footprint_case.h"
static fogrt__footprint shim_footprint(void)
{
    fogrt__footprint F = footprint_case();
    fogrt__footprint_bound(&F);
    return F;
}

/* kind 0: Henyey-Greenstein (param g, around wo); 1: the glow around a lamp in direction
   wo (chapter 6); 2: the cosine hemisphere around +z; 3: the uniform sphere; 4: the
   negative control, HG sampled at g but its pdf given at 0.95 g (must be rejected); 5: the
   footprint above, seen from the point wo (both ways mixed outside its sphere, the lamp's
   cone alone inside it); 6: the negative control, that footprint sampled the same way but
   its pdf given as the lamp's cone's alone (must be rejected); 7: two HG lobes (appendix G),
   param the row of HG2 below; 8: Rayleigh (G); 9: the negative control, two lobes (row
   param) sampled but the pdf given with the weights swapped (w for 1 - w). */
static const float HG2[3][3] = {{0.8f, -0.4f, 0.7f}, {0.95f, -0.7f, 0.5f}, {-0.3f, 0.6f, 0.25f}};   /* g1, g2, w */
void chi2_sample(int kind, float param, float wx, float wy, float wz, const float *u1, const float *u2, float *out, int n)
{
    fogrt_vec3 wo = v3(wx, wy, wz);
    fogrt__footprint F = shim_footprint();
    float pdf;
    int i;
    for (i = 0; i < n; ++i) {
        fogrt_vec3 w;
        if (kind == 5 || kind == 6) { if (!fogrt__sample_footprint(&F, wo, u1[i], u2[i], &w)) w = v3(0.0f, 0.0f, 0.0f); }   /* never here */
        else if (kind == 0 || kind == 4) w = fogrt_sample_hg(param, wo, u1[i], u2[i], &pdf);
        else if (kind == 7 || kind == 9) { const float *h = HG2[(int)param]; w = fogrt_sample_hg2(h[0], h[1], h[2], wo, u1[i], u2[i], &pdf); }
        else if (kind == 8) w = fogrt_sample_rayleigh(wo, u1[i], u2[i], &pdf);
        else if (kind == 1) w = fogrt_sample_glow(wo, u1[i], u2[i], &pdf);
        else if (kind == 2) w = fogrt_sample_cosine_hemisphere(u1[i], u2[i]);
        else w = fogrt_sample_uniform_sphere(u1[i], u2[i]);
        put(out, i, w);
    }
}
void chi2_pdf(int kind, float param, float wx, float wy, float wz, const float *wi, float *out, int n)
{
    fogrt_vec3 wo = v3(wx, wy, wz);
    fogrt__footprint F = shim_footprint();
    int i;
    for (i = 0; i < n; ++i) {
        fogrt_vec3 w = get(wi, i);
        if (kind == 5) out[i] = fogrt__footprint_pdf(&F, wo, w);
        else if (kind == 6) out[i] = fogrt__footprint_cone_pdf(&F, wo, w);
        else if (kind == 0) out[i] = fogrt_hg_pdf(param, wo, w);
        else if (kind == 7) { const float *h = HG2[(int)param]; out[i] = fogrt_hg2_pdf(h[0], h[1], h[2], wo, w); }
        else if (kind == 9) { const float *h = HG2[(int)param]; out[i] = fogrt_hg2_pdf(h[0], h[1], 1.0f - h[2], wo, w); }
        else if (kind == 8) out[i] = fogrt_rayleigh_pdf(wo, w);
        else if (kind == 4) out[i] = fogrt_hg_pdf(0.95f * param, wo, w);
        else if (kind == 1) out[i] = fogrt_glow_pdf(wo, w);
        else if (kind == 2) out[i] = fogrt_cosine_hemisphere_pdf(w.z);   /* 0 below the horizon */
        else out[i] = fogrt_uniform_sphere_pdf();
    }
}
