/* Step 7: Algorithm 1 with eq. 13 and Russian roulette (paper section 3.4).

   A path tracer of your own, over fogrt's public building blocks, that fogrt_render runs in
   place of its own integrator (coursework.h, "Steps 7 and 8", gives the rules the checker's
   images follow). Follow the ray: the nearer of the surface hit (fogrt_scene_intersect) and
   a fog collision (free flight, your step 1) is the next vertex; light sampling there (your
   step 6); a new direction from HG in fog (step 3) or from the BSDF on a surface (step 5, or
   fogrt_sample_bsdf in the frame of fogrt_scene_surface), multiplying the throughput by eq.
   13's weight; then Russian roulette. Without MIS here: emission found by a ray counts only
   when that ray is the camera ray.

   Eq. 13, L_i = f_r g(w_i) cos(theta) / pdf: theta is the angle between the NEW direction
   w_i (the sampled ray, which goes on to hit the next surface: the paper's "hitting ray" is
   that ray of the recursive call) and the surface normal, as in eq. 3's cos(theta_i); not
   the angle of the ray that arrived. For cosine-weighted diffuse sampling f cos / pdf is the
   reflectance (fogrt_sample_bsdf's weight); after HG sampling in fog there is no cosine and
   the weight is p_HG / pdf = 1.

   Check it:  make check-step STEP=7           (pictures in build/coursework/step7_*.png)  */
#include <math.h>
#include "coursework.h"

fogrt_vec3 cw_path_radiance(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user)
{
    const cw_path_settings *set = (const cw_path_settings *)user;
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f};
    /* TODO: beta = 1; depth = 0; loop:
         vertex: surface or fog collision (beta *= albedo in fog); the camera ray's emission;
         stop when the ray leaves the scene, or when depth reaches set->max_depth (unless -1);
         L += beta * direct light at the vertex;
         sample the next direction, beta *= f cos / pdf (eq. 13); ++depth;
         after set->rr_depth events: continue with probability q, and then ... */
    (void)scene; (void)o; (void)d; (void)rng; (void)set;
    return L;
}
