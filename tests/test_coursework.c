/* test_coursework.c - the coursework kit's checker is itself tested (docs/coursework.md,
   examples/coursework/). For every step: the reference solution passes every check, each
   wrong solution under tests/coursework/wrong/ fails the check meant to catch it with the
   message a student is meant to read, and the skeleton as shipped fails at least one check.

   One program holds them all: each file is included with its functions renamed (cw_X ->
   <variant>_X) and handed to the checker as pointers, so a reference, its wrong twins and
   the skeleton run side by side with the same seeds the student's run uses. No pictures
   are written here (make coursework-solutions and make check-step write them).            */
#include <stdio.h>
#include <string.h>
#include "unity.h"
/* Public API only: make test links this program with one shared build of the
   implementation (compiled with FOGRT_TESTS_SHARED_IMPL) instead of compiling it again. */
#ifndef FOGRT_TESTS_SHARED_IMPL
#define FOGRT_IMPLEMENTATION
#endif
#include "fogrt.h"
#include "examples/coursework/check.h"

void setUp(void) {}
void tearDown(void) {}

/* examples/coursework/solutions/step1_free_flight.c */
#define cw_sample_free_flight ref1_sample_free_flight
#define cw_free_flight_pdf ref1_free_flight_pdf
#include "examples/coursework/solutions/step1_free_flight.c"
#undef cw_sample_free_flight
#undef cw_free_flight_pdf
static cw_fns ref1_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_free_flight = ref1_sample_free_flight;
    f.free_flight_pdf = ref1_free_flight_pdf;
    return f;
}

/* examples/coursework/step1_free_flight.c */
#define cw_sample_free_flight skel1_sample_free_flight
#define cw_free_flight_pdf skel1_free_flight_pdf
#include "examples/coursework/step1_free_flight.c"
#undef cw_sample_free_flight
#undef cw_free_flight_pdf
static cw_fns skel1_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_free_flight = skel1_sample_free_flight;
    f.free_flight_pdf = skel1_free_flight_pdf;
    return f;
}

/* tests/coursework/wrong/step1_log_u.c */
#define cw_sample_free_flight w1_log_u_sample_free_flight
#define cw_free_flight_pdf w1_log_u_free_flight_pdf
#include "tests/coursework/wrong/step1_log_u.c"
#undef cw_sample_free_flight
#undef cw_free_flight_pdf
static cw_fns w1_log_u_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_free_flight = w1_log_u_sample_free_flight;
    f.free_flight_pdf = w1_log_u_free_flight_pdf;
    return f;
}

/* tests/coursework/wrong/step1_times_sigma.c */
#define cw_sample_free_flight w1_times_sigma_sample_free_flight
#define cw_free_flight_pdf w1_times_sigma_free_flight_pdf
#include "tests/coursework/wrong/step1_times_sigma.c"
#undef cw_sample_free_flight
#undef cw_free_flight_pdf
static cw_fns w1_times_sigma_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_free_flight = w1_times_sigma_sample_free_flight;
    f.free_flight_pdf = w1_times_sigma_free_flight_pdf;
    return f;
}

/* tests/coursework/wrong/step1_pdf_no_sigma.c */
#define cw_sample_free_flight w1_pdf_no_sigma_sample_free_flight
#define cw_free_flight_pdf w1_pdf_no_sigma_free_flight_pdf
#include "tests/coursework/wrong/step1_pdf_no_sigma.c"
#undef cw_sample_free_flight
#undef cw_free_flight_pdf
static cw_fns w1_pdf_no_sigma_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_free_flight = w1_pdf_no_sigma_sample_free_flight;
    f.free_flight_pdf = w1_pdf_no_sigma_free_flight_pdf;
    return f;
}

/* examples/coursework/solutions/step2_transmittance.c */
#define cw_transmittance ref2_transmittance
#define cw_transmittance_estimate ref2_transmittance_estimate
#include "examples/coursework/solutions/step2_transmittance.c"
#undef cw_transmittance
#undef cw_transmittance_estimate
static cw_fns ref2_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.transmittance = ref2_transmittance;
    f.transmittance_estimate = ref2_transmittance_estimate;
    return f;
}

/* examples/coursework/step2_transmittance.c */
#define cw_transmittance skel2_transmittance
#define cw_transmittance_estimate skel2_transmittance_estimate
#include "examples/coursework/step2_transmittance.c"
#undef cw_transmittance
#undef cw_transmittance_estimate
static cw_fns skel2_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.transmittance = skel2_transmittance;
    f.transmittance_estimate = skel2_transmittance_estimate;
    return f;
}

/* tests/coursework/wrong/step2_linear.c */
#define cw_transmittance w2_linear_transmittance
#define cw_transmittance_estimate w2_linear_transmittance_estimate
#include "tests/coursework/wrong/step2_linear.c"
#undef cw_transmittance
#undef cw_transmittance_estimate
static cw_fns w2_linear_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.transmittance = w2_linear_transmittance;
    f.transmittance_estimate = w2_linear_transmittance_estimate;
    return f;
}

/* tests/coursework/wrong/step2_estimator_collision.c */
#define cw_transmittance w2_estimator_collision_transmittance
#define cw_transmittance_estimate w2_estimator_collision_transmittance_estimate
#include "tests/coursework/wrong/step2_estimator_collision.c"
#undef cw_transmittance
#undef cw_transmittance_estimate
static cw_fns w2_estimator_collision_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.transmittance = w2_estimator_collision_transmittance;
    f.transmittance_estimate = w2_estimator_collision_transmittance_estimate;
    return f;
}

/* examples/coursework/solutions/step3_hg_phase.c */
#define cw_hg_phase ref3_hg_phase
#define cw_sample_hg_mu ref3_sample_hg_mu
#define cw_sample_hg ref3_sample_hg
#include "examples/coursework/solutions/step3_hg_phase.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns ref3_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = ref3_hg_phase;
    f.sample_hg_mu = ref3_sample_hg_mu;
    f.sample_hg = ref3_sample_hg;
    return f;
}

/* examples/coursework/step3_hg_phase.c */
#define cw_hg_phase skel3_hg_phase
#define cw_sample_hg_mu skel3_sample_hg_mu
#define cw_sample_hg skel3_sample_hg
#include "examples/coursework/step3_hg_phase.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns skel3_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = skel3_hg_phase;
    f.sample_hg_mu = skel3_sample_hg_mu;
    f.sample_hg = skel3_sample_hg;
    return f;
}

/* tests/coursework/wrong/step3_flipped_g.c */
#define cw_hg_phase w3_flipped_g_hg_phase
#define cw_sample_hg_mu w3_flipped_g_sample_hg_mu
#define cw_sample_hg w3_flipped_g_sample_hg
#include "tests/coursework/wrong/step3_flipped_g.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns w3_flipped_g_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = w3_flipped_g_hg_phase;
    f.sample_hg_mu = w3_flipped_g_sample_hg_mu;
    f.sample_hg = w3_flipped_g_sample_hg;
    return f;
}

/* tests/coursework/wrong/step3_no_g0.c */
#define cw_hg_phase w3_no_g0_hg_phase
#define cw_sample_hg_mu w3_no_g0_sample_hg_mu
#define cw_sample_hg w3_no_g0_sample_hg
#include "tests/coursework/wrong/step3_no_g0.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns w3_no_g0_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = w3_no_g0_hg_phase;
    f.sample_hg_mu = w3_no_g0_sample_hg_mu;
    f.sample_hg = w3_no_g0_sample_hg;
    return f;
}

/* tests/coursework/wrong/step3_half_phi.c */
#define cw_hg_phase w3_half_phi_hg_phase
#define cw_sample_hg_mu w3_half_phi_sample_hg_mu
#define cw_sample_hg w3_half_phi_sample_hg
#include "tests/coursework/wrong/step3_half_phi.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns w3_half_phi_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = w3_half_phi_hg_phase;
    f.sample_hg_mu = w3_half_phi_sample_hg_mu;
    f.sample_hg = w3_half_phi_sample_hg;
    return f;
}

/* tests/coursework/wrong/step3_no_4pi.c */
#define cw_hg_phase w3_no_4pi_hg_phase
#define cw_sample_hg_mu w3_no_4pi_sample_hg_mu
#define cw_sample_hg w3_no_4pi_sample_hg
#include "tests/coursework/wrong/step3_no_4pi.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns w3_no_4pi_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = w3_no_4pi_hg_phase;
    f.sample_hg_mu = w3_no_4pi_sample_hg_mu;
    f.sample_hg = w3_no_4pi_sample_hg;
    return f;
}

/* examples/coursework/solutions/step4_bvh_split.c */
#define cw_split_cost ref4_split_cost
#define cw_best_split ref4_best_split
#include "examples/coursework/solutions/step4_bvh_split.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns ref4_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = ref4_split_cost;
    f.best_split = ref4_best_split;
    return f;
}

/* examples/coursework/step4_bvh_split.c */
#define cw_split_cost skel4_split_cost
#define cw_best_split skel4_best_split
#include "examples/coursework/step4_bvh_split.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns skel4_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = skel4_split_cost;
    f.best_split = skel4_best_split;
    return f;
}

/* tests/coursework/wrong/step4_volume_swapped.c */
#define cw_split_cost w4_volume_swapped_split_cost
#define cw_best_split w4_volume_swapped_best_split
#include "tests/coursework/wrong/step4_volume_swapped.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns w4_volume_swapped_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = w4_volume_swapped_split_cost;
    f.best_split = w4_volume_swapped_best_split;
    return f;
}

/* tests/coursework/wrong/step4_sah_no_area.c */
#define cw_split_cost w4_sah_no_area_split_cost
#define cw_best_split w4_sah_no_area_best_split
#include "tests/coursework/wrong/step4_sah_no_area.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns w4_sah_no_area_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = w4_sah_no_area_split_cost;
    f.best_split = w4_sah_no_area_best_split;
    return f;
}

/* tests/coursework/wrong/step4_empty_side.c */
#define cw_split_cost w4_empty_side_split_cost
#define cw_best_split w4_empty_side_best_split
#include "tests/coursework/wrong/step4_empty_side.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns w4_empty_side_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = w4_empty_side_split_cost;
    f.best_split = w4_empty_side_best_split;
    return f;
}

/* tests/coursework/wrong/step4_best_cost_unscaled.c */
#define cw_split_cost w4_best_cost_unscaled_split_cost
#define cw_best_split w4_best_cost_unscaled_best_split
#include "tests/coursework/wrong/step4_best_cost_unscaled.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns w4_best_cost_unscaled_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = w4_best_cost_unscaled_split_cost;
    f.best_split = w4_best_cost_unscaled_best_split;
    return f;
}

/* examples/coursework/solutions/step5_bsdf.c */
#define cw_sample_diffuse ref5_sample_diffuse
#define cw_diffuse_pdf ref5_diffuse_pdf
#define cw_sample_mirror ref5_sample_mirror
#define cw_fresnel_schlick ref5_fresnel_schlick
#define cw_sample_glass ref5_sample_glass
#include "examples/coursework/solutions/step5_bsdf.c"
#undef cw_sample_diffuse
#undef cw_diffuse_pdf
#undef cw_sample_mirror
#undef cw_fresnel_schlick
#undef cw_sample_glass
static cw_fns ref5_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_diffuse = ref5_sample_diffuse;
    f.diffuse_pdf = ref5_diffuse_pdf;
    f.sample_mirror = ref5_sample_mirror;
    f.fresnel_schlick = ref5_fresnel_schlick;
    f.sample_glass = ref5_sample_glass;
    return f;
}

/* examples/coursework/step5_bsdf.c */
#define cw_sample_diffuse skel5_sample_diffuse
#define cw_diffuse_pdf skel5_diffuse_pdf
#define cw_sample_mirror skel5_sample_mirror
#define cw_fresnel_schlick skel5_fresnel_schlick
#define cw_sample_glass skel5_sample_glass
#include "examples/coursework/step5_bsdf.c"
#undef cw_sample_diffuse
#undef cw_diffuse_pdf
#undef cw_sample_mirror
#undef cw_fresnel_schlick
#undef cw_sample_glass
static cw_fns skel5_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_diffuse = skel5_sample_diffuse;
    f.diffuse_pdf = skel5_diffuse_pdf;
    f.sample_mirror = skel5_sample_mirror;
    f.fresnel_schlick = skel5_fresnel_schlick;
    f.sample_glass = skel5_sample_glass;
    return f;
}

/* tests/coursework/wrong/step5_missing_pdf.c */
#define cw_sample_diffuse w5_missing_pdf_sample_diffuse
#define cw_diffuse_pdf w5_missing_pdf_diffuse_pdf
#define cw_sample_mirror w5_missing_pdf_sample_mirror
#define cw_fresnel_schlick w5_missing_pdf_fresnel_schlick
#define cw_sample_glass w5_missing_pdf_sample_glass
#include "tests/coursework/wrong/step5_missing_pdf.c"
#undef cw_sample_diffuse
#undef cw_diffuse_pdf
#undef cw_sample_mirror
#undef cw_fresnel_schlick
#undef cw_sample_glass
static cw_fns w5_missing_pdf_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_diffuse = w5_missing_pdf_sample_diffuse;
    f.diffuse_pdf = w5_missing_pdf_diffuse_pdf;
    f.sample_mirror = w5_missing_pdf_sample_mirror;
    f.fresnel_schlick = w5_missing_pdf_fresnel_schlick;
    f.sample_glass = w5_missing_pdf_sample_glass;
    return f;
}

/* tests/coursework/wrong/step5_schlick_cos_i.c */
#define cw_sample_diffuse w5_schlick_cos_i_sample_diffuse
#define cw_diffuse_pdf w5_schlick_cos_i_diffuse_pdf
#define cw_sample_mirror w5_schlick_cos_i_sample_mirror
#define cw_fresnel_schlick w5_schlick_cos_i_fresnel_schlick
#define cw_sample_glass w5_schlick_cos_i_sample_glass
#include "tests/coursework/wrong/step5_schlick_cos_i.c"
#undef cw_sample_diffuse
#undef cw_diffuse_pdf
#undef cw_sample_mirror
#undef cw_fresnel_schlick
#undef cw_sample_glass
static cw_fns w5_schlick_cos_i_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_diffuse = w5_schlick_cos_i_sample_diffuse;
    f.diffuse_pdf = w5_schlick_cos_i_diffuse_pdf;
    f.sample_mirror = w5_schlick_cos_i_sample_mirror;
    f.fresnel_schlick = w5_schlick_cos_i_fresnel_schlick;
    f.sample_glass = w5_schlick_cos_i_sample_glass;
    return f;
}

/* tests/coursework/wrong/step5_uniform.c */
#define cw_sample_diffuse w5_uniform_sample_diffuse
#define cw_diffuse_pdf w5_uniform_diffuse_pdf
#define cw_sample_mirror w5_uniform_sample_mirror
#define cw_fresnel_schlick w5_uniform_fresnel_schlick
#define cw_sample_glass w5_uniform_sample_glass
#include "tests/coursework/wrong/step5_uniform.c"
#undef cw_sample_diffuse
#undef cw_diffuse_pdf
#undef cw_sample_mirror
#undef cw_fresnel_schlick
#undef cw_sample_glass
static cw_fns w5_uniform_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_diffuse = w5_uniform_sample_diffuse;
    f.diffuse_pdf = w5_uniform_diffuse_pdf;
    f.sample_mirror = w5_uniform_sample_mirror;
    f.fresnel_schlick = w5_uniform_fresnel_schlick;
    f.sample_glass = w5_uniform_sample_glass;
    return f;
}

/* examples/coursework/solutions/step6_direct.c */
#define cw_direct_surface ref6_direct_surface
#define cw_direct_fog ref6_direct_fog
#include "examples/coursework/solutions/step6_direct.c"
#undef cw_direct_surface
#undef cw_direct_fog
static cw_fns ref6_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.direct_surface = ref6_direct_surface;
    f.direct_fog = ref6_direct_fog;
    return f;
}

/* examples/coursework/step6_direct.c */
#define cw_direct_surface skel6_direct_surface
#define cw_direct_fog skel6_direct_fog
#include "examples/coursework/step6_direct.c"
#undef cw_direct_surface
#undef cw_direct_fog
static cw_fns skel6_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.direct_surface = skel6_direct_surface;
    f.direct_fog = skel6_direct_fog;
    return f;
}

/* tests/coursework/wrong/step6_no_cos.c */
#define cw_direct_surface w6_no_cos_direct_surface
#define cw_direct_fog w6_no_cos_direct_fog
#include "tests/coursework/wrong/step6_no_cos.c"
#undef cw_direct_surface
#undef cw_direct_fog
static cw_fns w6_no_cos_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.direct_surface = w6_no_cos_direct_surface;
    f.direct_fog = w6_no_cos_direct_fog;
    return f;
}

/* tests/coursework/wrong/step6_no_pdf.c */
#define cw_direct_surface w6_no_pdf_direct_surface
#define cw_direct_fog w6_no_pdf_direct_fog
#include "tests/coursework/wrong/step6_no_pdf.c"
#undef cw_direct_surface
#undef cw_direct_fog
static cw_fns w6_no_pdf_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.direct_surface = w6_no_pdf_direct_surface;
    f.direct_fog = w6_no_pdf_direct_fog;
    return f;
}

/* tests/coursework/wrong/step6_no_transmittance.c */
#define cw_direct_surface w6_no_transmittance_direct_surface
#define cw_direct_fog w6_no_transmittance_direct_fog
#include "tests/coursework/wrong/step6_no_transmittance.c"
#undef cw_direct_surface
#undef cw_direct_fog
static cw_fns w6_no_transmittance_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.direct_surface = w6_no_transmittance_direct_surface;
    f.direct_fog = w6_no_transmittance_direct_fog;
    return f;
}

/* tests/coursework/wrong/step6_one_light.c */
#define cw_direct_surface w6_one_light_direct_surface
#define cw_direct_fog w6_one_light_direct_fog
#include "tests/coursework/wrong/step6_one_light.c"
#undef cw_direct_surface
#undef cw_direct_fog
static cw_fns w6_one_light_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.direct_surface = w6_one_light_direct_surface;
    f.direct_fog = w6_one_light_direct_fog;
    return f;
}

/* examples/coursework/solutions/step7_path.c: also the test that fogrt's public blocks reproduce its own
   Algorithm 1 (the checks compare with fogrt's image) */
#define cw_path_radiance ref7_path_radiance
#include "examples/coursework/solutions/step7_path.c"
#undef cw_path_radiance
static cw_fns ref7_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = ref7_path_radiance;
    return f;
}

/* examples/coursework/step7_path.c */
#define cw_path_radiance skel7_path_radiance
#include "examples/coursework/step7_path.c"
#undef cw_path_radiance
static cw_fns skel7_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = skel7_path_radiance;
    return f;
}

/* tests/coursework/wrong/step7_no_q.c */
#define cw_path_radiance w7_no_q_path_radiance
#include "tests/coursework/wrong/step7_no_q.c"
#undef cw_path_radiance
static cw_fns w7_no_q_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_no_q_path_radiance;
    return f;
}

/* tests/coursework/wrong/step7_no_albedo.c */
#define cw_path_radiance w7_no_albedo_path_radiance
#include "tests/coursework/wrong/step7_no_albedo.c"
#undef cw_path_radiance
static cw_fns w7_no_albedo_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_no_albedo_path_radiance;
    return f;
}

/* tests/coursework/wrong/step7_fog_bias3.c */
#define cw_path_radiance w7_fog_bias3_path_radiance
#include "tests/coursework/wrong/step7_fog_bias3.c"
#undef cw_path_radiance
static cw_fns w7_fog_bias3_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_fog_bias3_path_radiance;
    return f;
}

/* tests/coursework/wrong/step7_hg_over_pdf.c */
#define cw_path_radiance w7_hg_over_pdf_path_radiance
#include "tests/coursework/wrong/step7_hg_over_pdf.c"
#undef cw_path_radiance
static cw_fns w7_hg_over_pdf_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_hg_over_pdf_path_radiance;
    return f;
}

/* tests/coursework/wrong/step7_flight_sigma_s.c */
#define cw_path_radiance w7_flight_sigma_s_path_radiance
#include "tests/coursework/wrong/step7_flight_sigma_s.c"
#undef cw_path_radiance
static cw_fns w7_flight_sigma_s_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_flight_sigma_s_path_radiance;
    return f;
}

/* tests/coursework/wrong/step7_rr_always.c */
#define cw_path_radiance w7_rr_always_path_radiance
#include "tests/coursework/wrong/step7_rr_always.c"
#undef cw_path_radiance
static cw_fns w7_rr_always_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_rr_always_path_radiance;
    return f;
}

/* examples/coursework/solutions/step8_mis.c */
#define cw_mis_weight ref8_mis_weight
#define cw_mis_radiance ref8_mis_radiance
#include "examples/coursework/solutions/step8_mis.c"
#undef cw_mis_weight
#undef cw_mis_radiance
static cw_fns ref8_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.mis_weight = ref8_mis_weight;
    f.mis_radiance = ref8_mis_radiance;
    return f;
}

/* examples/coursework/step8_mis.c */
#define cw_mis_weight skel8_mis_weight
#define cw_mis_radiance skel8_mis_radiance
#include "examples/coursework/step8_mis.c"
#undef cw_mis_weight
#undef cw_mis_radiance
static cw_fns skel8_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.mis_weight = skel8_mis_weight;
    f.mis_radiance = skel8_mis_radiance;
    return f;
}

/* tests/coursework/wrong/step8_emission_full_weight.c */
#define cw_mis_weight w8_full_mis_weight
#define cw_mis_radiance w8_full_mis_radiance
#include "tests/coursework/wrong/step8_emission_full_weight.c"
#undef cw_mis_weight
#undef cw_mis_radiance
static cw_fns w8_full_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.mis_weight = w8_full_mis_weight;
    f.mis_radiance = w8_full_mis_radiance;
    return f;
}

/* tests/coursework/wrong/step8_no_mis.c */
#define cw_mis_weight w8_no_mis_mis_weight
#define cw_mis_radiance w8_no_mis_mis_radiance
#include "tests/coursework/wrong/step8_no_mis.c"
#undef cw_mis_weight
#undef cw_mis_radiance
static cw_fns w8_no_mis_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.mis_weight = w8_no_mis_mis_weight;
    f.mis_radiance = w8_no_mis_mis_radiance;
    return f;
}

/* tests/coursework/wrong/step8_balance.c */
#define cw_mis_weight w8_balance_mis_weight
#define cw_mis_radiance w8_balance_mis_radiance
#include "tests/coursework/wrong/step8_balance.c"
#undef cw_mis_weight
#undef cw_mis_radiance
static cw_fns w8_balance_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.mis_weight = w8_balance_mis_weight;
    f.mis_radiance = w8_balance_mis_radiance;
    return f;
}

/* examples/coursework/solutions/step9_equiangular.c: fogrt's equiangular sampler, which is
   Part II's (B); the skeleton and the wrong twins below use none of Part II */
#ifndef FOGRT_MINIMAL
#define cw_sample_equiangular ref9_sample_equiangular
#define cw_equiangular_pdf ref9_equiangular_pdf
#include "examples/coursework/solutions/step9_equiangular.c"
#undef cw_sample_equiangular
#undef cw_equiangular_pdf
static cw_fns ref9_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_equiangular = ref9_sample_equiangular;
    f.equiangular_pdf = ref9_equiangular_pdf;
    return f;
}
#endif

/* examples/coursework/step9_equiangular.c */
#define cw_sample_equiangular skel9_sample_equiangular
#define cw_equiangular_pdf skel9_equiangular_pdf
#include "examples/coursework/step9_equiangular.c"
#undef cw_sample_equiangular
#undef cw_equiangular_pdf
static cw_fns skel9_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_equiangular = skel9_sample_equiangular;
    f.equiangular_pdf = skel9_equiangular_pdf;
    return f;
}

/* tests/coursework/wrong/step9_no_delta.c */
#define cw_sample_equiangular w9_no_delta_sample_equiangular
#define cw_equiangular_pdf w9_no_delta_equiangular_pdf
#include "tests/coursework/wrong/step9_no_delta.c"
#undef cw_sample_equiangular
#undef cw_equiangular_pdf
static cw_fns w9_no_delta_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_equiangular = w9_no_delta_sample_equiangular;
    f.equiangular_pdf = w9_no_delta_equiangular_pdf;
    return f;
}

/* tests/coursework/wrong/step9_pdf_no_h.c: wraps fogrt's equiangular sampler (Part II) */
#ifndef FOGRT_MINIMAL
#define cw_sample_equiangular w9_pdf_no_h_sample_equiangular
#define cw_equiangular_pdf w9_pdf_no_h_equiangular_pdf
#include "tests/coursework/wrong/step9_pdf_no_h.c"
#undef cw_sample_equiangular
#undef cw_equiangular_pdf
static cw_fns w9_pdf_no_h_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_equiangular = w9_pdf_no_h_sample_equiangular;
    f.equiangular_pdf = w9_pdf_no_h_equiangular_pdf;
    return f;
}
#endif

/* tests/coursework/wrong/step3_mu_reversed.c */
#define cw_hg_phase w3_mu_reversed_hg_phase
#define cw_sample_hg_mu w3_mu_reversed_sample_hg_mu
#define cw_sample_hg w3_mu_reversed_sample_hg
#include "tests/coursework/wrong/step3_mu_reversed.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns w3_mu_reversed_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = w3_mu_reversed_hg_phase;
    f.sample_hg_mu = w3_mu_reversed_sample_hg_mu;
    f.sample_hg = w3_mu_reversed_sample_hg;
    return f;
}

/* tests/coursework/wrong/step3_flipped_g_float.c */
#define cw_hg_phase w3_flipped_g_float_hg_phase
#define cw_sample_hg_mu w3_flipped_g_float_sample_hg_mu
#define cw_sample_hg w3_flipped_g_float_sample_hg
#include "tests/coursework/wrong/step3_flipped_g_float.c"
#undef cw_hg_phase
#undef cw_sample_hg_mu
#undef cw_sample_hg
static cw_fns w3_flipped_g_float_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.hg_phase = w3_flipped_g_float_hg_phase;
    f.sample_hg_mu = w3_flipped_g_float_sample_hg_mu;
    f.sample_hg = w3_flipped_g_float_sample_hg;
    return f;
}

/* tests/coursework/wrong/step4_longest_axis.c */
#define cw_split_cost w4_longest_axis_split_cost
#define cw_best_split w4_longest_axis_best_split
#include "tests/coursework/wrong/step4_longest_axis.c"
#undef cw_split_cost
#undef cw_best_split
static cw_fns w4_longest_axis_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.split_cost = w4_longest_axis_split_cost;
    f.best_split = w4_longest_axis_best_split;
    return f;
}

/* tests/coursework/wrong/step5_eta_not_inverted.c */
#define cw_sample_diffuse w5_eta_not_inverted_sample_diffuse
#define cw_diffuse_pdf w5_eta_not_inverted_diffuse_pdf
#define cw_sample_mirror w5_eta_not_inverted_sample_mirror
#define cw_fresnel_schlick w5_eta_not_inverted_fresnel_schlick
#define cw_sample_glass w5_eta_not_inverted_sample_glass
#include "tests/coursework/wrong/step5_eta_not_inverted.c"
#undef cw_sample_diffuse
#undef cw_diffuse_pdf
#undef cw_sample_mirror
#undef cw_fresnel_schlick
#undef cw_sample_glass
static cw_fns w5_eta_not_inverted_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_diffuse = w5_eta_not_inverted_sample_diffuse;
    f.diffuse_pdf = w5_eta_not_inverted_diffuse_pdf;
    f.sample_mirror = w5_eta_not_inverted_sample_mirror;
    f.fresnel_schlick = w5_eta_not_inverted_fresnel_schlick;
    f.sample_glass = w5_eta_not_inverted_sample_glass;
    return f;
}

/* tests/coursework/wrong/step7_cos_wo.c */
#define cw_path_radiance w7_cos_wo_path_radiance
#include "tests/coursework/wrong/step7_cos_wo.c"
#undef cw_path_radiance
static cw_fns w7_cos_wo_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.path_radiance = w7_cos_wo_path_radiance;
    return f;
}

/* tests/coursework/wrong/step9_far_end.c */
#define cw_sample_equiangular w9_far_end_sample_equiangular
#define cw_equiangular_pdf w9_far_end_equiangular_pdf
#include "tests/coursework/wrong/step9_far_end.c"
#undef cw_sample_equiangular
#undef cw_equiangular_pdf
static cw_fns w9_far_end_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.sample_equiangular = w9_far_end_sample_equiangular;
    f.equiangular_pdf = w9_far_end_equiangular_pdf;
    return f;
}

/* tests/coursework/wrong/step8_fog_bias3.c */
#define cw_mis_weight w8_fog_bias3_mis_weight
#define cw_mis_radiance w8_fog_bias3_mis_radiance
#include "tests/coursework/wrong/step8_fog_bias3.c"
#undef cw_mis_weight
#undef cw_mis_radiance
static cw_fns w8_fog_bias3_fns(void)
{
    cw_fns f;
    memset(&f, 0, sizeof f);
    f.mis_weight = w8_fog_bias3_mis_weight;
    f.mis_radiance = w8_fog_bias3_mis_radiance;
    return f;
}

static cw_run run_;

/* Runs one step quietly on f; returns the run. */
static const cw_run *run_step(int step, cw_fns f)
{
    memset(&run_, 0, sizeof run_);
    run_.quiet = 1;
    TEST_ASSERT_TRUE_MESSAGE(cw_run_step(step, &f, &run_) >= 0, "no such step");
    return &run_;
}

static void expect_all_pass(int step, cw_fns f)
{
    const cw_run *r = run_step(step, f);
    const cw_result *bad = cw_first_failure(r);
    char msg[1600];
    snprintf(msg, sizeof msg, "step %d reference: %d of %d checks passed in %.2f s", step, r->passed, r->count, r->seconds);
    TEST_MESSAGE(msg);
    if (bad) TEST_FAIL_MESSAGE(bad->line);
    TEST_ASSERT_GREATER_THAN(0, r->count);
}

static void expect_caught(int step, const char *what, cw_fns f, const char *check, const char *text)
{
    const cw_run *r = run_step(step, f);
    const cw_result *hit = cw_find_failure(r, check, text);
    char msg[1800];
    if (hit) {
        snprintf(msg, sizeof msg, "%s caught (%d of %d checks failed): %s", what, r->count - r->passed, r->count, hit->line);
        TEST_MESSAGE(msg);
        return;
    }
    {
        const cw_result *first = cw_first_failure(r);
        snprintf(msg, sizeof msg, "%s: no failing %s saying \"%s\"; first failure: %s", what, check, text,
                 first ? first->line : "none (every check passed)");
        TEST_FAIL_MESSAGE(msg);
    }
}

static void expect_skeleton_fails(int step, cw_fns f)
{
    const cw_run *r = run_step(step, f);
    char msg[300];
    snprintf(msg, sizeof msg, "step %d skeleton as shipped: %d of %d checks fail", step, r->count - r->passed, r->count);
    TEST_MESSAGE(msg);
    {
        int i;
        for (i = 0; i < r->count; ++i)
            if (r->r[i].pass) {
                snprintf(msg, sizeof msg, "the skeleton as shipped passes %s: a check that an empty function passes grades "
                         "nothing", r->r[i].name);
                TEST_FAIL_MESSAGE(msg);
            }
    }
}

static void test_step1_reference_passes(void) { expect_all_pass(1, ref1_fns()); }
static void test_step1_skeleton_fails(void) { expect_skeleton_fails(1, skel1_fns()); }
static void test_step1_wrong_log_u(void)
{
    expect_caught(1, "tests/coursework/wrong/step1_log_u.c", w1_log_u_fns(), "step1.inverse_cdf",
                  "t gets smaller as u grows");
}
static void test_step1_wrong_times_sigma(void)
{
    expect_caught(1, "tests/coursework/wrong/step1_times_sigma.c", w1_times_sigma_fns(), "step1.chi2",
                  "multiplying by sigma_t instead of dividing");
}
static void test_step1_wrong_pdf_no_sigma(void)
{
    expect_caught(1, "tests/coursework/wrong/step1_pdf_no_sigma.c", w1_pdf_no_sigma_fns(), "step1.pdf_integral",
                  "integrates to 1/sigma_t");
}
static void test_step2_reference_passes(void) { expect_all_pass(2, ref2_fns()); }
static void test_step2_skeleton_fails(void) { expect_skeleton_fails(2, skel2_fns()); }
static void test_step2_wrong_linear(void)
{
    expect_caught(2, "tests/coursework/wrong/step2_linear.c", w2_linear_fns(), "step2.eq8",
                  "first-order approximation");
}
static void test_step2_wrong_estimator_collision(void)
{
    expect_caught(2, "tests/coursework/wrong/step2_estimator_collision.c", w2_estimator_collision_fns(), "step2.estimator",
                  "averages 1 - T");
}
static void test_step3_reference_passes(void) { expect_all_pass(3, ref3_fns()); }
static void test_step3_skeleton_fails(void) { expect_skeleton_fails(3, skel3_fns()); }
static void test_step3_wrong_flipped_g(void)
{
    expect_caught(3, "tests/coursework/wrong/step3_flipped_g.c", w3_flipped_g_fns(), "step3.mu_chi2",
                  "is g's sign flipped?");
}
static void test_step3_wrong_no_g0(void)
{
    expect_caught(3, "tests/coursework/wrong/step3_no_g0.c", w3_no_g0_fns(), "step3.edges",
                  "g = 0 gave mu = nan");
}
static void test_step3_wrong_half_phi(void)
{
    expect_caught(3, "tests/coursework/wrong/step3_half_phi.c", w3_half_phi_fns(), "step3.direction_chi2",
                  "azimuth sectors around d are (nearly) empty");
}
static void test_step3_wrong_no_4pi(void)
{
    expect_caught(3, "tests/coursework/wrong/step3_no_4pi.c", w3_no_4pi_fns(), "step3.phase_integral",
                  "integrates to 4 pi");
}
static void test_step4_reference_passes(void) { expect_all_pass(4, ref4_fns()); }
static void test_step4_skeleton_fails(void) { expect_skeleton_fails(4, skel4_fns()); }
static void test_step4_wrong_volume_swapped(void)
{
    expect_caught(4, "tests/coursework/wrong/step4_volume_swapped.c", w4_volume_swapped_fns(), "step4.volume_cost",
                  "summed the wrong way");
}
static void test_step4_wrong_sah_no_area(void)
{
    expect_caught(4, "tests/coursework/wrong/step4_sah_no_area.c", w4_sah_no_area_fns(), "step4.sah_cost",
                  "divide by the parent's area");
}
static void test_step4_wrong_empty_side(void)
{
    expect_caught(4, "tests/coursework/wrong/step4_empty_side.c", w4_empty_side_fns(), "step4.edges",
                  "no plane splits them");
}
static void test_step4_wrong_best_cost_unscaled(void)
{
    expect_caught(4, "tests/coursework/wrong/step4_best_cost_unscaled.c", w4_best_cost_unscaled_fns(), "step4.sah_best_cost",
                  "lacks the division by the parent's area");
}
static void test_step5_reference_passes(void) { expect_all_pass(5, ref5_fns()); }
static void test_step5_skeleton_fails(void) { expect_skeleton_fails(5, skel5_fns()); }
static void test_step5_wrong_missing_pdf(void)
{
    expect_caught(5, "tests/coursework/wrong/step5_missing_pdf.c", w5_missing_pdf_fns(), "step5.diffuse_weight",
                  "forget to divide by the pdf");
}
static void test_step5_wrong_schlick_cos_i(void)
{
    expect_caught(5, "tests/coursework/wrong/step5_schlick_cos_i.c", w5_schlick_cos_i_fns(), "step5.schlick",
                  "you used the incident cosine");
}
static void test_step5_wrong_uniform(void)
{
    expect_caught(5, "tests/coursework/wrong/step5_uniform.c", w5_uniform_fns(), "step5.diffuse_chi2",
                  "looks like uniform hemisphere sampling");
}
static void test_step6_reference_passes(void) { expect_all_pass(6, ref6_fns()); }
static void test_step6_skeleton_fails(void) { expect_skeleton_fails(6, skel6_fns()); }
static void test_step6_wrong_no_cos(void)
{
    expect_caught(6, "tests/coursework/wrong/step6_no_cos.c", w6_no_cos_fns(), "step6.surface_formula",
                  "cosine between wi and the normal");
}
static void test_step6_wrong_no_pdf(void)
{
    expect_caught(6, "tests/coursework/wrong/step6_no_pdf.c", w6_no_pdf_fns(), "step6.area_estimate",
                  "missing 1/pdf?");
}
static void test_step6_wrong_no_transmittance(void)
{
    expect_caught(6, "tests/coursework/wrong/step6_no_transmittance.c", w6_no_transmittance_fns(), "step6.fog_formula",
                  "transmittance exp(-sigma_t dist) of the shadow ray");
}
static void test_step6_wrong_one_light(void)
{
    expect_caught(6, "tests/coursework/wrong/step6_one_light.c", w6_one_light_fns(), "step6.every_light",
                  "ONE sample of EVERY light");
}
static void test_step7_reference_passes(void) { expect_all_pass(7, ref7_fns()); }
static void test_step7_skeleton_fails(void) { expect_skeleton_fails(7, skel7_fns()); }
static void test_step7_wrong_no_q(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_no_q.c", w7_no_q_fns(), "step7.roulette", "missing 1/q?");
}
static void test_step7_wrong_no_albedo(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_no_albedo.c", w7_no_albedo_fns(), "step7.direct",
                  "Is the albedo applied at fog collisions?");
}
static void test_step7_wrong_fog_bias3(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_fog_bias3.c", w7_fog_bias3_fns(), "step7.fog_single",
                  "too bright by a factor 1.03");
}
static void test_step7_wrong_hg_over_pdf(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_hg_over_pdf.c", w7_hg_over_pdf_fns(), "step7.bounces",
                  "times as noisy as fogrt's");
}
static void test_step7_wrong_flight_sigma_s(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_flight_sigma_s.c", w7_flight_sigma_s_fns(), "step7.fog_single",
                  "free flights drawn with sigma_s");
}
static void test_step7_wrong_rr_always(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_rr_always.c", w7_rr_always_fns(), "step7.depth",
                  "roulette played before rr_depth");
}
static void test_step8_reference_passes(void) { expect_all_pass(8, ref8_fns()); }
static void test_step8_skeleton_fails(void) { expect_skeleton_fails(8, skel8_fns()); }
static void test_step8_wrong_emission_full_weight(void)
{
    expect_caught(8, "tests/coursework/wrong/step8_emission_full_weight.c", w8_full_fns(), "step8.box",
                  "emission counted at full weight?");
}
static void test_step8_wrong_no_mis(void)
{
    expect_caught(8, "tests/coursework/wrong/step8_no_mis.c", w8_no_mis_fns(), "step8.noise",
                  "Is the strategy of BSDF and phase sampling missing");
}
static void test_step8_wrong_balance(void)
{
    expect_caught(8, "tests/coursework/wrong/step8_balance.c", w8_balance_fns(), "step8.weights",
                  "the kit asks for the power heuristic");
}
static void test_step9_reference_passes(void)
{
#ifdef FOGRT_MINIMAL
    TEST_IGNORE_MESSAGE("needs Part II of fogrt.h (B: equiangular sampling): built with FOGRT_MINIMAL");
#else
    expect_all_pass(9, ref9_fns());
#endif
}
static void test_step9_skeleton_fails(void) { expect_skeleton_fails(9, skel9_fns()); }
static void test_step9_wrong_no_delta(void)
{
    expect_caught(9, "tests/coursework/wrong/step9_no_delta.c", w9_no_delta_fns(), "step9.chi2",
                  "instead of the light's closest approach");
}
static void test_step9_wrong_pdf_no_h(void)
{
#ifdef FOGRT_MINIMAL
    TEST_IGNORE_MESSAGE("needs Part II of fogrt.h (B: equiangular sampling): built with FOGRT_MINIMAL");
#else
    expect_caught(9, "tests/coursework/wrong/step9_pdf_no_h.c", w9_pdf_no_h_fns(), "step9.pdf_integral",
                  "the factor h in the numerator is missing");
#endif
}

static void test_w3_mu_reversed(void)
{
    expect_caught(3, "tests/coursework/wrong/step3_mu_reversed.c", w3_mu_reversed_fns(), "step3.edges",
                  "failed on the convention alone");
}
static void test_w3_flipped_g_float(void)
{
    expect_caught(3, "tests/coursework/wrong/step3_flipped_g_float.c", w3_flipped_g_float_fns(), "step3.eq9",
                  "is g's sign flipped?");
}
static void test_w4_longest_axis(void)
{
    expect_caught(4, "tests/coursework/wrong/step4_longest_axis.c", w4_longest_axis_fns(), "step4.sah_choice",
                  "did you search one axis only");
}
static void test_w5_eta_not_inverted(void)
{
    expect_caught(5, "tests/coursework/wrong/step5_eta_not_inverted.c", w5_eta_not_inverted_fns(), "step5.glass_dirs",
                  "you used the ratio of entering the glass");
}
static void test_w7_cos_wo(void)
{
    expect_caught(7, "tests/coursework/wrong/step7_cos_wo.c", w7_cos_wo_fns(), "step7.box",
                  "instead of the new direction wi");
}
static void test_w9_far_end(void)
{
    expect_caught(9, "tests/coursework/wrong/step9_far_end.c", w9_far_end_fns(), "step9.edges",
                  "failed on the convention alone");
}

static void test_w8_fog_bias3(void)
{
    expect_caught(8, "tests/coursework/wrong/step8_fog_bias3.c", w8_fog_bias3_fns(), "step8.fog_single",
                  "too bright by a factor 1.03");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_step1_reference_passes);
    RUN_TEST(test_step1_skeleton_fails);
    RUN_TEST(test_step1_wrong_log_u);
    RUN_TEST(test_step1_wrong_times_sigma);
    RUN_TEST(test_step1_wrong_pdf_no_sigma);
    RUN_TEST(test_step2_reference_passes);
    RUN_TEST(test_step2_skeleton_fails);
    RUN_TEST(test_step2_wrong_linear);
    RUN_TEST(test_step2_wrong_estimator_collision);
    RUN_TEST(test_step3_reference_passes);
    RUN_TEST(test_step3_skeleton_fails);
    RUN_TEST(test_step3_wrong_flipped_g);
    RUN_TEST(test_step3_wrong_no_g0);
    RUN_TEST(test_step3_wrong_half_phi);
    RUN_TEST(test_step3_wrong_no_4pi);
    RUN_TEST(test_step4_reference_passes);
    RUN_TEST(test_step4_skeleton_fails);
    RUN_TEST(test_step4_wrong_volume_swapped);
    RUN_TEST(test_step4_wrong_sah_no_area);
    RUN_TEST(test_step4_wrong_empty_side);
    RUN_TEST(test_step4_wrong_best_cost_unscaled);
    RUN_TEST(test_step5_reference_passes);
    RUN_TEST(test_step5_skeleton_fails);
    RUN_TEST(test_step5_wrong_missing_pdf);
    RUN_TEST(test_step5_wrong_schlick_cos_i);
    RUN_TEST(test_step5_wrong_uniform);
    RUN_TEST(test_step6_reference_passes);
    RUN_TEST(test_step6_skeleton_fails);
    RUN_TEST(test_step6_wrong_no_cos);
    RUN_TEST(test_step6_wrong_no_pdf);
    RUN_TEST(test_step6_wrong_no_transmittance);
    RUN_TEST(test_step6_wrong_one_light);
    RUN_TEST(test_step7_reference_passes);
    RUN_TEST(test_step7_skeleton_fails);
    RUN_TEST(test_step7_wrong_no_q);
    RUN_TEST(test_step7_wrong_no_albedo);
    RUN_TEST(test_step7_wrong_fog_bias3);
    RUN_TEST(test_step7_wrong_hg_over_pdf);
    RUN_TEST(test_step7_wrong_flight_sigma_s);
    RUN_TEST(test_step7_wrong_rr_always);
    RUN_TEST(test_step8_reference_passes);
    RUN_TEST(test_step8_skeleton_fails);
    RUN_TEST(test_step8_wrong_emission_full_weight);
    RUN_TEST(test_step8_wrong_no_mis);
    RUN_TEST(test_step8_wrong_balance);
    RUN_TEST(test_step9_reference_passes);
    RUN_TEST(test_step9_skeleton_fails);
    RUN_TEST(test_step9_wrong_no_delta);
    RUN_TEST(test_step9_wrong_pdf_no_h);
    RUN_TEST(test_w3_mu_reversed);
    RUN_TEST(test_w3_flipped_g_float);
    RUN_TEST(test_w4_longest_axis);
    RUN_TEST(test_w5_eta_not_inverted);
    RUN_TEST(test_w7_cos_wo);
    RUN_TEST(test_w9_far_end);
    RUN_TEST(test_w8_fog_bias3);
    return UNITY_END();
}
