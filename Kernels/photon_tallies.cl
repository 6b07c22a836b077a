// photon_tallies.cl: layout of the photon pass's books, the one definition shared by the host
// (vtkPhotonTracer.cxx includes this file as a C++ header) and photon_trace.cl (prepended to it
// by the host). Macros only, so it reads the same in C++ and OpenCL C.
//
// Tallies (fixed point, REFRACTA_FIXED_SCALE): tallies[3 * T + c], RGB channel c of book T.
// Counters (plain 64-bit integers): counters[K].
#ifndef PHOTON_TALLIES_CL
#define PHOTON_TALLIES_CL

#define PHOTON_TALLY_EMITTED 0
#define PHOTON_TALLY_ABSORBED 1
#define PHOTON_TALLY_ESCAPED 2
#define PHOTON_TALLY_SCATTERED 3
#define PHOTON_TALLY_REMAINING 4 /* at the step cap or on an invalid state */
#define PHOTON_TALLY_KILLED 5    /* by Russian roulette */
#define PHOTON_TALLY_GAINED 6    /* added to roulette survivors */
#define PHOTON_TALLY_SURFACE 7   /* absorbed by surfaces (vtkRefractaSurfaceSet) */
#define PHOTON_TALLY_BOOKS 8 /* books a photon adds when it finishes (photon_finish) */
#define PHOTON_TALLY_INTERFACE_REFLECTED 8   /* power reflected by dielectric interfaces */
#define PHOTON_TALLY_INTERFACE_TRANSMITTED 9 /* power refracted through dielectric interfaces */
#define PHOTON_TALLY_ALL_BOOKS 10 /* with the books added at each interface event */
#define PHOTON_TALLY_COUNT (3 * PHOTON_TALLY_ALL_BOOKS) /* longs in the tallies buffer */

#define PHOTON_COUNTER_MARCHED 0
#define PHOTON_COUNTER_MISSED 1
#define PHOTON_COUNTER_ESCAPED 2   /* outcomes 2..5 and 8 index their counters */
#define PHOTON_COUNTER_ROULETTE 3
#define PHOTON_COUNTER_STEP_CAP 4
#define PHOTON_COUNTER_INVALID 5
#define PHOTON_COUNTER_STEPS 6
#define PHOTON_COUNTER_PIECES 7
#define PHOTON_COUNTER_SURFACE 8      /* outcome: ended on a surface (black, or albedo roulette) */
#define PHOTON_COUNTER_SURFACE_HITS 9 /* surface hits of all photons */
#define PHOTON_COUNTER_INTERFACE_REFLECTIONS 10   /* reflections at dielectric interfaces */
#define PHOTON_COUNTER_INTERFACE_TRANSMISSIONS 11 /* refractions at dielectric interfaces */
#define PHOTON_COUNTER_COUNT 12                   /* longs in the counters buffer */

#define PHOTON_STATE_FLOAT4S 9 /* float4 of one photon's state in photon_march_chunk */

#endif
