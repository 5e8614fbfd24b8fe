/* Wrong step 4: cw_split_cost is right, but cw_best_split compares the SAH's sums
   N_l A_l + N_r A_r (which orders a node's planes the same way) and returns that sum as the
   cost. The plane is right; only step4.sah_best_cost sees the cost. */
#include "../../../examples/coursework/coursework.h"

static float w4b_area(const cw_aabb *b)
{
    float x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    return 2.0f * (x * y + y * z + z * x);
}
static float w4b_volume(const cw_aabb *b)
{
    return (b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]) * (b->hi[2] - b->lo[2]);
}
static void w4b_grow(cw_aabb *b, const cw_aabb *c, int *have)
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
    if (heuristic == CW_VOLUME) return (float)n_left * w4b_volume(left) + (float)n_right * w4b_volume(right);
    return 1.0f + ((float)n_left * w4b_area(left) + (float)n_right * w4b_area(right)) / w4b_area(parent);
}

cw_split cw_best_split(int heuristic, const cw_aabb *parent, const cw_bins *bins)
{
    cw_split best;
    int a, k, j;
    (void)parent;
    best.axis = 0; best.plane = -1; best.cost = 0.0f;
    for (a = 0; a < 3; ++a)
        for (k = 1; k < bins->n_bins; ++k) {
            cw_aabb l, r;
            int nl = 0, nr = 0, hl = 0, hr = 0;
            float cost;
            for (j = 0; j < bins->n_bins; ++j) {
                if (!bins->count[a][j]) continue;
                if (j < k) { w4b_grow(&l, &bins->box[a][j], &hl); nl += bins->count[a][j]; }
                else { w4b_grow(&r, &bins->box[a][j], &hr); nr += bins->count[a][j]; }
            }
            if (!nl || !nr) continue;
            if (heuristic == CW_VOLUME) cost = (float)nl * w4b_volume(&l) + (float)nr * w4b_volume(&r);
            else cost = (float)nl * w4b_area(&l) + (float)nr * w4b_area(&r);
            if (best.plane < 0 || cost < best.cost) { best.axis = a; best.plane = k; best.cost = cost; }
        }
    return best;
}
