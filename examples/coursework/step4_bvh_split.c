/* Step 4: choosing a BVH split (paper section 2.1, eq. 1-2).

   A BVH node is split by a plane; the candidates come from binning the primitives'
   centroids (coursework.h explains cw_bins). Write the cost of one split under the surface
   area heuristic and under the paper's volume heuristic (eq. 1), and the search for the
   cheapest plane over the three axes (eq. 2).

   Check it:  make check-step STEP=4           (pictures in build/coursework/step4_*.png)  */
#include "coursework.h"

float cw_split_cost(int heuristic, const cw_aabb *parent, const cw_aabb *left, int n_left,
                    const cw_aabb *right, int n_right)
{
    /* TODO: CW_SAH: 1 + (N_l A_l + N_r A_r) / A;  CW_VOLUME: eq. 1 */
    (void)heuristic; (void)parent; (void)left; (void)n_left; (void)right; (void)n_right;
    return 0.0f;
}

cw_split cw_best_split(int heuristic, const cw_aabb *parent, const cw_bins *bins)
{
    cw_split s;
    /* TODO: for every axis and plane k = 1 .. n_bins - 1, gather both sides' counts and
       boxes from the bins, skip planes with an empty side, keep the cheapest */
    (void)heuristic; (void)parent; (void)bins;
    s.axis = 0; s.plane = -1; s.cost = 0.0f;
    return s;
}
