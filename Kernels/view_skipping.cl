// view_skipping.cl: the view pass's empty-space skipping (-DREFRACTA_SKIP; view_pass.cl, "Empty-space
// skipping", says how the occupancy grid is built and used). Compiled before view_pass.cl.

#ifdef REFRACTA_SKIP
// Length, along unit direction d from grid-local point x (in the box), of the empty space ahead:
// the run of consecutive empty macro cells (occupancy & mask == 0) that starts at x's cell, 0
// when that cell is occupied, INFINITY when nothing active lies ahead (the caller clamps it to the
// box exit). First a slab test against the bounding box of the active cells (cells activeLo ..
// activeHi, inclusive): a ray that misses it sees only empty space; otherwise an incremental 3D
// DDA (Amanatides and Woo 1987) walks the cells from where the ray enters it. It goes on through
// the run of occupied cells that ends the empty run, so that *nextCheck receives the distance
// from x before which the caller need not ask again (where the next empty cell starts along the
// straight line; for a curved ray only a hint, which costs skipping, never correctness).
inline float refracta_empty_run(float3 x, float3 d, float3 lo, float3 hi, float3 cellExtent,
  int4 cellDims, int4 activeLo, int4 activeHi, __global const uchar* occupancy, uint mask,
  float* nextCheck)
{
  const float3 boxLo = lo + convert_float3(activeLo.xyz) * cellExtent;
  const float3 boxHi = fmin(lo + convert_float3(activeHi.xyz + 1) * cellExtent, hi);
  float a0, a1;
  if (activeLo.w == 0 || !refracta_intersect_box(x, d, boxLo, boxHi, &a0, &a1))
  {
    *nextCheck = INFINITY; // no active cell (activeLo.w == 0) or none ahead: empty to the exit
    return INFINITY;
  }
  // Outside the active box, everything up to its entry a0 is empty: start the walk there.
  const float3 xa = x + a0 * d;
  const float3 u = (xa - lo) / cellExtent;
  int3 c = clamp(convert_int3(floor(u)), activeLo.xyz, activeHi.xyz);
  const int3 step = select((int3)(-1), (int3)(1), d > (float3)(0.0f));
  const float3 inv = (float3)(1.0f) / d;
  const float3 boundary =
    lo + convert_float3(c + select((int3)(0), (int3)(1), d > (float3)(0.0f))) * cellExtent;
  float3 tMax = select(a0 + (boundary - xa) * inv, (float3)(INFINITY), d == (float3)(0.0f));
  const float3 tDelta = select(cellExtent * fabs(inv), (float3)(INFINITY), d == (float3)(0.0f));
  float t = a0;
  float run = -1.0f; // set when the first occupied cell is met
  const int maxCells = cellDims.x + cellDims.y + cellDims.z + 3;
  for (int it = 0; it < maxCells; ++it)
  {
    const bool occupied = (occupancy[refracta_voxel_index(cellDims, c.x, c.y, c.z)] & mask) != 0;
    if (run < 0.0f && occupied)
    {
      run = t; // the empty run ends here; walk on through the occupied cells
    }
    else if (run >= 0.0f && !occupied)
    {
      *nextCheck = t; // the next empty cell starts here
      return run;
    }
    const float tOut = fmin(tMax.x, fmin(tMax.y, tMax.z));
    t = fmax(tOut, t);
    if (tMax.x <= tOut)
    {
      c.x += step.x;
      tMax.x += tDelta.x;
    }
    else if (tMax.y <= tOut)
    {
      c.y += step.y;
      tMax.y += tDelta.y;
    }
    else
    {
      c.z += step.z;
      tMax.z += tDelta.z;
    }
    if (any(c < activeLo.xyz) || any(c > activeHi.xyz))
    {
      // Left the active box (convex): nothing active lies beyond.
      *nextCheck = run < 0.0f ? INFINITY : t;
      return run < 0.0f ? INFINITY : run;
    }
  }
  *nextCheck = t;
  return run < 0.0f ? t : run;
}
#endif
