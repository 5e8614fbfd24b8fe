/* Wrong step 4: planes with an empty side are not skipped; the empty side's box is left
   as it was, so such a "split" can look cheapest (flat nodes under eq. 1 cost 0 anyway).
   Caught by step4.edges (and the choice checks when an empty side wins). */
#include "../../../examples/coursework/coursework.h"

static float w4e_area(const cw_aabb *b)
{
    float x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    return 2.0f * (x * y + y * z + z * x);
}
static float w4e_volume(const cw_aabb *b)
{
    return (b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]) * (b->hi[2] - b->lo[2]);
}
static void w4e_grow(cw_aabb *b, const cw_aabb *c, int *have)
{
    int j;
    if (!*have) { *b = *c; *have = 1; return; }
    for (j = 0; j < 3; ++j) {
        if (c->lo[j] < b->lo[j]) b->lo[j] = c->lo[j];
        if (c->hi[j] > b->hi[j]) b->hi[j] = c->hi[j];
    }
}

float cw_split_cost(int heuristic, const cw_aabb *parent, const cw_aabb *left, int n_left,
                    const cw_aabb *right, int n_right)
{
    if (heuristic == CW_VOLUME) return (float)n_left * w4e_volume(left) + (float)n_right * w4e_volume(right);
    return 1.0f + ((float)n_left * w4e_area(left) + (float)n_right * w4e_area(right)) / w4e_area(parent);
}

/* Gathers both sides of every plane from the bins. */
cw_split cw_best_split(int heuristic, const cw_aabb *parent, const cw_bins *bins)
{
    cw_split best;
    int a, k, j;
    best.axis = 0; best.plane = -1; best.cost = 0.0f;
    for (a = 0; a < 3; ++a)
        for (k = 1; k < bins->n_bins; ++k) {
            cw_aabb l, r;
            int nl = 0, nr = 0, hl = 0, hr = 0;
            float cost;
            for (j = 0; j < bins->n_bins; ++j) {
                if (!bins->count[a][j]) continue;
                if (j < k) { w4e_grow(&l, &bins->box[a][j], &hl); nl += bins->count[a][j]; }
                else { w4e_grow(&r, &bins->box[a][j], &hr); nr += bins->count[a][j]; }
            }
            if (!nl) { l = r; } if (!nr) { r = l; }
            cost = cw_split_cost(heuristic, parent, &l, nl, &r, nr);
            if (best.plane < 0 || cost < best.cost) { best.axis = a; best.plane = k; best.cost = cost; }
        }
    return best;
}
