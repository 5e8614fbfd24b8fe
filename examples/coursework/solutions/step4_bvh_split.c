/* Reference solution of step 4 (docs/coursework.md). fogrt's builder prices its planes
   inside fogrt.h (chapter 9) with no public function per split, so the kit carries its own:
   the same formulas, written for one node's bins. */
#include "../coursework.h"

static float ref4_area(const cw_aabb *b)
{
    float x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    return 2.0f * (x * y + y * z + z * x);
}
static float ref4_volume(const cw_aabb *b)
{
    return (b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]) * (b->hi[2] - b->lo[2]);
}

float cw_split_cost(int heuristic, const cw_aabb *parent, const cw_aabb *left, int n_left,
                    const cw_aabb *right, int n_right)
{
    if (heuristic == CW_VOLUME)                    /* eq. 1 */
        return (float)n_left * ref4_volume(left) + (float)n_right * ref4_volume(right);
    return 1.0f + ((float)n_left * ref4_area(left) + (float)n_right * ref4_area(right)) / ref4_area(parent);
}

/* Sweeps each axis once: the left side grows bin by bin, and the right side of plane k is
   the union of bins k..n-1, built from the far end first. */
cw_split cw_best_split(int heuristic, const cw_aabb *parent, const cw_bins *bins)
{
    cw_split best;
    int a, k, j, n = bins->n_bins;
    best.axis = 0; best.plane = -1; best.cost = 0.0f;
    for (a = 0; a < 3; ++a) {
        cw_aabb right[CW_MAX_BINS], left;
        int right_n[CW_MAX_BINS], left_n = 0, have_left = 0;
        for (k = n - 1; k >= 0; --k) {
            int c = bins->count[a][k];
            right_n[k] = c + (k + 1 < n ? right_n[k + 1] : 0);
            if (k + 1 < n) right[k] = right[k + 1];
            if (c) {
                if (k + 1 < n && right_n[k + 1]) {
                    for (j = 0; j < 3; ++j) {
                        if (bins->box[a][k].lo[j] < right[k].lo[j]) right[k].lo[j] = bins->box[a][k].lo[j];
                        if (bins->box[a][k].hi[j] > right[k].hi[j]) right[k].hi[j] = bins->box[a][k].hi[j];
                    }
                } else right[k] = bins->box[a][k];
            }
        }
        for (k = 1; k < n; ++k) {
            int c = bins->count[a][k - 1];
            float cost;
            if (c) {
                if (have_left) {
                    for (j = 0; j < 3; ++j) {
                        if (bins->box[a][k - 1].lo[j] < left.lo[j]) left.lo[j] = bins->box[a][k - 1].lo[j];
                        if (bins->box[a][k - 1].hi[j] > left.hi[j]) left.hi[j] = bins->box[a][k - 1].hi[j];
                    }
                } else { left = bins->box[a][k - 1]; have_left = 1; }
                left_n += c;
            }
            if (!left_n || !right_n[k]) continue;        /* one side empty: not a split */
            cost = cw_split_cost(heuristic, parent, &left, left_n, &right[k], right_n[k]);
            if (best.plane < 0 || cost < best.cost) { best.axis = a; best.plane = k; best.cost = cost; }
        }
    }
    return best;
}
