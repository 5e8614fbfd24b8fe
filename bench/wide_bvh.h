/* bench/wide_bvh.h - a faster binary BVH build, drafted for fogrt.h (not yet in it).

   The wide BVH itself (chapter 10b) is in fogrt.h. This file keeps the draft of a faster
   binned build of the binary tree (section 9b below) for bench/wide_dev.c, which checks it
   against fogrt.h's build (same SAH cost, same answers against brute force) and times it:
   it makes about 0.7x the instructions of fogrt__bvh_build. It moves into fogrt.h once it is
   split into functions the size of the rest of the header. Include it after fogrt.h's
   implementation. */
#ifndef FOGRT_BENCH_WIDE_BVH_H
#define FOGRT_BENCH_WIDE_BVH_H
/* ------------------------------------------------------------------------------------------
   9b. A faster binned build (replaces fogrt__bvh_build of chapter 9; same tree layout, same
   heuristic, same leaf rule)
   fogrt__bvh_build reads each node's primitives six times (centroid bounds, three axes,
   partition, two child bounds), one coordinate at a time and through the index array. This
   version makes two passes per node over a compact array of primitive boxes that is itself
   reordered (each box is 2 x 4 floats, so one SSE instruction takes the minimum of a whole
   corner):
     1. one binning pass for all three axes at once: the centroid of a box is (lo + hi) / 2,
        its three bin numbers come from one multiply, and each of the three bins it falls in
        grows by two min/max instructions. The cheapest plane is then found from the bins
        exactly as fogrt__split_axis does, and the two child boxes are the unions of the bins
        on each side (exact: a bin's box holds its primitives' boxes);
     2. one partition pass that swaps boxes by their bin on the chosen axis (the same bin
        computation as step 1, so the two sides get exactly the primitives the cost was
        computed for: no re-test against the plane and no "all on one side" case), and grows
        the centroid bounds each child needs for its own binning on the way.
   Differences from fogrt__bvh_build: the split follows the bin boundaries exactly (the old
   build re-tests centroid < plane, which can move a primitive lying on the plane), so the
   trees can differ in a few nodes. Needs 32 bytes per primitive of temporary memory;
   returns false when out of memory. The 4-float vector below is SSE, or four plain floats
   with the same results (FOGRT_WBVH_NO_SIMD).
   ------------------------------------------------------------------------------------------ */
#ifdef FOGRT_WBVH_SSE
typedef __m128 fogrt__f4;
#define fogrt__f4_load(p) _mm_loadu_ps(p)
#define fogrt__f4_store(p, a) _mm_storeu_ps(p, a)
#define fogrt__f4_set1(x) _mm_set1_ps(x)
#define fogrt__f4_min(a, b) _mm_min_ps(a, b)          /* a < b ? a : b, per lane */
#define fogrt__f4_max(a, b) _mm_max_ps(a, b)          /* a > b ? a : b, per lane */
#define fogrt__f4_add(a, b) _mm_add_ps(a, b)
#define fogrt__f4_sub(a, b) _mm_sub_ps(a, b)
#define fogrt__f4_mul(a, b) _mm_mul_ps(a, b)
FOGRT__HOT void fogrt__f4_trunc(fogrt__f4 a, int32_t *out)
{
    _mm_storeu_si128((__m128i *)(void *)out, _mm_cvttps_epi32(a));
}
#else
typedef struct fogrt__f4 { float v[4]; } fogrt__f4;
FOGRT__HOT fogrt__f4 fogrt__f4_load(const float *p) { fogrt__f4 r; memcpy(r.v, p, sizeof r.v); return r; }
FOGRT__HOT void fogrt__f4_store(float *p, fogrt__f4 a) { memcpy(p, a.v, sizeof a.v); }
FOGRT__HOT fogrt__f4 fogrt__f4_set1(float x) { fogrt__f4 r; r.v[0] = r.v[1] = r.v[2] = r.v[3] = x; return r; }
#define FOGRT__F4_OP(name, expr) \
    FOGRT__HOT fogrt__f4 name(fogrt__f4 a, fogrt__f4 b) { fogrt__f4 r; int i_; for (i_ = 0; i_ < 4; ++i_) { float x = a.v[i_], y = b.v[i_]; r.v[i_] = (expr); } return r; }
FOGRT__F4_OP(fogrt__f4_min, x < y ? x : y)
FOGRT__F4_OP(fogrt__f4_max, x > y ? x : y)
FOGRT__F4_OP(fogrt__f4_add, x + y)
FOGRT__F4_OP(fogrt__f4_sub, x - y)
FOGRT__F4_OP(fogrt__f4_mul, x * y)
#undef FOGRT__F4_OP
FOGRT__HOT void fogrt__f4_trunc(fogrt__f4 a, int32_t *out)   /* inputs already in [0, nb - 1] */
{
    int i;
    for (i = 0; i < 4; ++i) out[i] = (int32_t)a.v[i];
}
#endif

typedef struct fogrt__brec { float lo[4], hi[4]; } fogrt__brec;   /* lane 3 unused (0) */
typedef struct fogrt__bjob { uint32_t node, depth; float clo[4], chi[4]; } fogrt__bjob;

/* Bin numbers of a box's centroid on the three axes: clamp((c - lo) * scale, 0, nb - 1),
   truncated; a NaN (a flat axis) lands in bin 0, as in fogrt__split_axis. */
FOGRT__HOT void fogrt__brec_bins(const fogrt__brec *r, fogrt__f4 lo, fogrt__f4 scale, fogrt__f4 top, int32_t *bin)
{
    fogrt__f4 c = fogrt__f4_mul(fogrt__f4_add(fogrt__f4_load(r->lo), fogrt__f4_load(r->hi)), fogrt__f4_set1(0.5f));
    fogrt__f4 f = fogrt__f4_mul(fogrt__f4_sub(c, lo), scale);
    f = fogrt__f4_max(f, fogrt__f4_set1(0.0f));        /* NaN -> 0 (max returns its 2nd operand) */
    f = fogrt__f4_min(f, top);
    fogrt__f4_trunc(f, bin);
}

/* Box and centroid bounds of count records (for the root and for the rare balanced splits). */
FOGRT__PRIVATE void fogrt__brec_bounds(const fogrt__brec *r, uint32_t count, fogrt_bvh_node *node, float *clo, float *chi)
{
    fogrt__f4 lo = fogrt__f4_set1(FLT_MAX), hi = fogrt__f4_set1(-FLT_MAX), cl = lo, ch = hi;
    float l[4], h[4];
    uint32_t i;
    int k;
    for (i = 0; i < count; ++i) {
        fogrt__f4 a = fogrt__f4_load(r[i].lo), b = fogrt__f4_load(r[i].hi);
        fogrt__f4 c = fogrt__f4_mul(fogrt__f4_add(a, b), fogrt__f4_set1(0.5f));
        lo = fogrt__f4_min(lo, a); hi = fogrt__f4_max(hi, b);
        cl = fogrt__f4_min(cl, c); ch = fogrt__f4_max(ch, c);
    }
    fogrt__f4_store(l, lo); fogrt__f4_store(h, hi);
    fogrt__f4_store(clo, cl); fogrt__f4_store(chi, ch);
    for (k = 0; k < 3; ++k) { node->bmin[k] = l[k]; node->bmax[k] = h[k]; }
}

FOGRT__PRIVATE bool fogrt__bvh_build_fast(fogrt__build *b, uint32_t prim_count, const fogrt_allocator *a)
{
    enum { MAXB = 64 };
    const fogrt_build_desc *d = &b->desc;
    fogrt__bjob stack[FOGRT__BVH_MAX_DEPTH + 2];
    uint32_t sp = 0, i;
    fogrt__brec *rec = (fogrt__brec *)fogrt__alloc(a, sizeof(fogrt__brec) * (size_t)prim_count);
    uint32_t *ids = b->idx;                            /* permuted together with rec */
    fogrt_bvh_node *root = &b->nodes[0];
    if (!rec) return false;
    for (i = 0; i < prim_count; ++i) {                 /* the records, in the order of idx */
        const fogrt__aabb *bx = &b->box[ids[i]];
        rec[i].lo[0] = bx->lo.x; rec[i].lo[1] = bx->lo.y; rec[i].lo[2] = bx->lo.z; rec[i].lo[3] = 0.0f;
        rec[i].hi[0] = bx->hi.x; rec[i].hi[1] = bx->hi.y; rec[i].hi[2] = bx->hi.z; rec[i].hi[3] = 0.0f;
    }
    memset(&b->nodes[1], 0, sizeof b->nodes[1]);          /* node 1: unused (pairs align) */
    root->left_first = 0;
    root->prim_count = prim_count;
    stack[0].node = 0; stack[0].depth = 0;
    fogrt__brec_bounds(rec, prim_count, root, stack[0].clo, stack[0].chi);
    sp = 1;
    b->node_count = 2;
    while (sp > 0) {
        fogrt__bjob job = stack[--sp];
        fogrt_bvh_node *node = &b->nodes[job.node];
        uint32_t first = node->left_first, count = node->prim_count, left_count = 0, l = 0;
        fogrt__brec *r = rec + first;
        uint32_t *rid = ids + first;
        float lclo[4], lchi[4], rclo[4], rchi[4];
        bool halve = false;
        int k;
        if (count <= 1) continue;
        if (job.depth >= FOGRT__BVH_SAH_DEPTH) {
            halve = true;
        } else {
            /* Step 1: bin all three axes in one pass, then sweep each axis. */
            float bin_lo[3][MAXB][4], bin_hi[3][MAXB][4], scale[4], best = FLT_MAX, leaf_cost, area;
            uint32_t bin_n[3][MAXB];
            bool ok[3];
            int nb = count < (uint32_t)d->bins ? (int)count : d->bins, best_axis = -1, best_k = 0, ax, kk;
            fogrt__f4 lo4, scale4, top4;
            fogrt__aabb nbox;
            if (nb == 1) nb = 2;
            for (ax = 0; ax < 3; ++ax) {
                scale[ax] = (float)nb / (job.chi[ax] - job.clo[ax]);
                ok[ax] = job.chi[ax] > job.clo[ax] && scale[ax] > 0.0f && scale[ax] < FLT_MAX;
                if (!ok[ax]) scale[ax] = 0.0f;           /* every centroid in bin 0 */
                for (kk = 0; kk < nb; ++kk) {
                    fogrt__f4_store(bin_lo[ax][kk], fogrt__f4_set1(FLT_MAX));
                    fogrt__f4_store(bin_hi[ax][kk], fogrt__f4_set1(-FLT_MAX));
                    bin_n[ax][kk] = 0;
                }
            }
            scale[3] = 0.0f;
            lo4 = fogrt__f4_load(job.clo); scale4 = fogrt__f4_load(scale); top4 = fogrt__f4_set1((float)(nb - 1));
            for (i = 0; i < count; ++i) {
                fogrt__f4 blo = fogrt__f4_load(r[i].lo), bhi = fogrt__f4_load(r[i].hi);
                int32_t bin[4];
                fogrt__brec_bins(&r[i], lo4, scale4, top4, bin);
                for (ax = 0; ax < 3; ++ax) {
                    float *bl = bin_lo[ax][bin[ax]], *bh = bin_hi[ax][bin[ax]];
                    bin_n[ax][bin[ax]]++;
                    fogrt__f4_store(bl, fogrt__f4_min(fogrt__f4_load(bl), blo));
                    fogrt__f4_store(bh, fogrt__f4_max(fogrt__f4_load(bh), bhi));
                }
            }
            for (ax = 0; ax < 3; ++ax) {                 /* the sweep of fogrt__split_axis */
                fogrt__aabb left_box = fogrt__aabb_empty(), right_box = fogrt__aabb_empty(), bb;
                uint32_t left_n = 0, right_n = 0;
                float left_cost[MAXB];
                if (!ok[ax]) continue;
                for (kk = 0; kk < nb - 1; ++kk) {
                    left_n += bin_n[ax][kk];
                    bb.lo = fogrt__v(bin_lo[ax][kk][0], bin_lo[ax][kk][1], bin_lo[ax][kk][2]);
                    bb.hi = fogrt__v(bin_hi[ax][kk][0], bin_hi[ax][kk][1], bin_hi[ax][kk][2]);
                    fogrt__aabb_union(&left_box, &bb);
                    left_cost[kk] = fogrt__side_cost(d, left_n, &left_box);
                }
                for (kk = nb - 1; kk > 0; --kk) {
                    float cost;
                    right_n += bin_n[ax][kk];
                    bb.lo = fogrt__v(bin_lo[ax][kk][0], bin_lo[ax][kk][1], bin_lo[ax][kk][2]);
                    bb.hi = fogrt__v(bin_hi[ax][kk][0], bin_hi[ax][kk][1], bin_hi[ax][kk][2]);
                    fogrt__aabb_union(&right_box, &bb);
                    if (right_n == 0 || right_n == count) continue;
                    cost = left_cost[kk - 1] + fogrt__side_cost(d, right_n, &right_box);
                    if (cost < best) { best = cost; best_axis = ax; best_k = kk; }
                }
            }
            /* The leaf rule of fogrt__find_split. */
            nbox.lo = fogrt__v(node->bmin[0], node->bmin[1], node->bmin[2]);
            nbox.hi = fogrt__v(node->bmax[0], node->bmax[1], node->bmax[2]);
            area = fogrt__aabb_area(&nbox);
            leaf_cost = d->c_int * (float)count;
            if (best_axis < 0) {
                if (count <= (uint32_t)d->max_leaf_size) continue;
                halve = true;                            /* all centroids coincide */
            } else if (d->heuristic == FOGRT_BVH_VOLUME ? count <= (uint32_t)d->max_leaf_size
                       : !(d->c_trav + d->c_int * best / FOGRT__MAX(area, FLT_MIN) < leaf_cost ||
                           count > (uint32_t)d->max_leaf_size)) {
                continue;                                /* a leaf */
            } else {
                /* Step 2: partition by bin, growing the children's centroid bounds. */
                uint32_t lo_i = 0, hi_i = count;
                fogrt__f4 lcl = fogrt__f4_set1(FLT_MAX), lch = fogrt__f4_set1(-FLT_MAX), rcl = lcl, rch = lch;
                fogrt__f4 sl = fogrt__f4_set1(FLT_MAX), sh = fogrt__f4_set1(-FLT_MAX);
                float tl[4], th[4];
                ax = best_axis;
                while (lo_i < hi_i) {
                    fogrt__f4 c = fogrt__f4_mul(fogrt__f4_add(fogrt__f4_load(r[lo_i].lo), fogrt__f4_load(r[lo_i].hi)), fogrt__f4_set1(0.5f));
                    int32_t bin[4];
                    fogrt__brec_bins(&r[lo_i], lo4, scale4, top4, bin);
                    if (bin[ax] < best_k) {
                        lcl = fogrt__f4_min(lcl, c); lch = fogrt__f4_max(lch, c);
                        ++lo_i;
                    } else {
                        fogrt__brec t = r[lo_i];
                        uint32_t tid = rid[lo_i];
                        rcl = fogrt__f4_min(rcl, c); rch = fogrt__f4_max(rch, c);
                        --hi_i;
                        r[lo_i] = r[hi_i]; r[hi_i] = t;
                        rid[lo_i] = rid[hi_i]; rid[hi_i] = tid;
                    }
                }
                fogrt__f4_store(lclo, lcl); fogrt__f4_store(lchi, lch);
                fogrt__f4_store(rclo, rcl); fogrt__f4_store(rchi, rch);
                left_count = lo_i;
                FOGRT_ASSERT(left_count > 0 && left_count < count);
                l = b->node_count;
                b->node_count += 2;
                for (kk = 0; kk < nb; ++kk) {            /* the children's boxes, from the bins */
                    if (kk == best_k) {
                        fogrt__f4_store(tl, sl); fogrt__f4_store(th, sh);
                        for (k = 0; k < 3; ++k) { b->nodes[l].bmin[k] = tl[k]; b->nodes[l].bmax[k] = th[k]; }
                        sl = fogrt__f4_set1(FLT_MAX); sh = fogrt__f4_set1(-FLT_MAX);
                    }
                    sl = fogrt__f4_min(sl, fogrt__f4_load(bin_lo[ax][kk]));
                    sh = fogrt__f4_max(sh, fogrt__f4_load(bin_hi[ax][kk]));
                }
                fogrt__f4_store(tl, sl); fogrt__f4_store(th, sh);
                for (k = 0; k < 3; ++k) { b->nodes[l + 1].bmin[k] = tl[k]; b->nodes[l + 1].bmax[k] = th[k]; }
            }
        }
        if (halve) {                                     /* balanced split, bounds by a pass */
            left_count = count / 2;
            l = b->node_count;
            b->node_count += 2;
            fogrt__brec_bounds(r, left_count, &b->nodes[l], lclo, lchi);
            fogrt__brec_bounds(r + left_count, count - left_count, &b->nodes[l + 1], rclo, rchi);
        }
        b->nodes[l].left_first = first;                  b->nodes[l].prim_count = left_count;
        b->nodes[l + 1].left_first = first + left_count; b->nodes[l + 1].prim_count = count - left_count;
        node->left_first = l;
        node->prim_count = 0;
        FOGRT_ASSERT(sp + 2 <= FOGRT__BVH_MAX_DEPTH + 2);
        stack[sp].node = l + 1; stack[sp].depth = job.depth + 1;
        for (k = 0; k < 4; ++k) { stack[sp].clo[k] = rclo[k]; stack[sp].chi[k] = rchi[k]; }
        ++sp;
        stack[sp].node = l; stack[sp].depth = job.depth + 1;
        for (k = 0; k < 4; ++k) { stack[sp].clo[k] = lclo[k]; stack[sp].chi[k] = lchi[k]; }
        ++sp;
    }
    fogrt__free(a, rec);
    return true;
}
#endif
