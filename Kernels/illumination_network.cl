// illumination_network.cl: one iteration of the illumination network of Szirmay-Kalos, Sbert and
// Umenhoffer (papers/002, section 3.3) on N particles and D global sample directions.
//
// Arrays (RGB interleaved, index ((p * D + i) * 3 + c)):
//   I[p, i]  incoming radiance of particle p from the line of direction i (light travelling along
//            omega_i), the illumination network;
//   O[q, i]  outgoing radiance of particle q along omega_i:
//              O[q, i] = (1 - alpha_q) I[q, i] + E[q, i] + a_q alpha_q sum_d I[q, d] W_q[d, i]
//   E[q, i]  emission plus the reflection of the direct light (host-computed, the paper's E);
//   V[p, i]  the visibility network: the particle seen from p against omega_i (its upstream
//            neighbour on the line of direction i through p), or -1 where none is seen.
// W_q[d, i] = P_q(omega_d, omega_i) 4 pi / D, the Henyey-Greenstein phase matrix of particle q's
// phase class, each row normalised so that sum_i W[d, i] = 1: the Monte Carlo quadrature of the
// paper, made to scatter exactly the power it intercepts (so the network's books close).
// One iteration (the paper's pixel shader, split in two so the D x D sum runs once per particle
// and direction instead of once per (p, i) pair that sees the particle):
//   ilnet_scatter:   O from I,                      work item (i, q), i fastest;
//   ilnet_propagate: I'[p, i] = V[p,i] < 0 ? sky : O[V[p, i], i],  work item (i, p);
//   ilnet_change:    per particle, max |I' - I| and max I' over i and c (convergence check).

__kernel void ilnet_scatter(__global const float* incoming, __global const float* emitted,
  __global const float* opacity, __global const float* albedo, __global const int* phaseClass,
  __global const float* phase, __global float* outgoing, const int D, const int N)
{
  const int i = get_global_id(0);
  const int q = get_global_id(1);
  if (i >= D || q >= N)
  {
    return;
  }
  __global const float* w = phase + (size_t)phaseClass[q] * D * D + i;
  __global const float* inq = incoming + (size_t)q * D * 3;
  float3 sum = (float3)(0.0f);
  for (int d = 0; d < D; ++d)
  {
    const float wd = w[(size_t)d * D];
    sum += wd * (float3)(inq[d * 3], inq[d * 3 + 1], inq[d * 3 + 2]);
  }
  const float3 alpha = vload3(q, opacity);
  const float3 a = vload3(q, albedo);
  const size_t k = (size_t)q * D + i;
  const float3 own = vload3(k, incoming);
  const float3 out = (1.0f - alpha) * own + vload3(k, emitted) + a * alpha * sum;
  vstore3(out, k, outgoing);
}

__kernel void ilnet_propagate(__global const int* visible, __global const float* outgoing,
  __global float* incoming, const float skyR, const float skyG, const float skyB, const int D,
  const int N)
{
  const int i = get_global_id(0);
  const int p = get_global_id(1);
  if (i >= D || p >= N)
  {
    return;
  }
  const size_t k = (size_t)p * D + i;
  const int vp = visible[k];
  const float3 value = vp < 0 ? (float3)(skyR, skyG, skyB) : vload3((size_t)vp * D + i, outgoing);
  vstore3(value, k, incoming);
}

__kernel void ilnet_change(__global const float* previous, __global const float* current,
  __global float* change, const int D, const int N)
{
  const int p = get_global_id(0);
  if (p >= N)
  {
    return;
  }
  float largestChange = 0.0f;
  float largest = 0.0f;
  for (int j = 0; j < D * 3; ++j)
  {
    const size_t k = (size_t)p * D * 3 + j;
    largestChange = fmax(largestChange, fabs(current[k] - previous[k]));
    largest = fmax(largest, current[k]);
  }
  change[2 * p] = largestChange;
  change[2 * p + 1] = largest;
}
