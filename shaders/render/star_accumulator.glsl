// The stars' light of a band before it joins the band's output
// (render/frame/star_pass.h): per band pixel four ints (r, g, b, unused), the
// linear sRGB radiance × exposure in fixed point, `star_fixed_point` counts
// per unit. Integer atomics make the sum of overlapping stars independent of
// the order the GPU runs them in (float atomics are neither core GL 4.5 nor
// associative): every node of a cluster, Mesa and NVIDIA add the same
// numbers. night_sky.comp reads each pixel once and zeroes it, so the buffer
// is all zeros between passes.
// star_splat.comp adds to single ints (atomics); night_sky.comp reads and
// clears a pixel's four at once (one 16-byte access: llvmpipe runs each
// storage access as a loop over the SIMD lanes), defining STAR_PIXELS.
#ifdef STAR_PIXELS
layout(std430, binding = STAR_ACCUMULATOR_BINDING) buffer StarAccumulator { ivec4 star_pixels[]; };
#else
layout(std430, binding = STAR_ACCUMULATOR_BINDING) buffer StarAccumulator { int star_accumulator[]; };
#endif
