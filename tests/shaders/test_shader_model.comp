#version 450 core
// The constants and the WavelengthData layout that the shader model defines,
// as atmosphere_common.glsl sees them (tests/render/shader_interface_test.cpp):
// values[0..4] = PI, INV_4PI, PENNDORF_A, PENNDORF_B, SERIES_LIMIT, then from
// values[8] one real4 per named field of group `wavelength_group`: Rayleigh
// scattering, Mie scattering, Mie extinction, g1, g2, α, ground albedo and, with
// absorbers, the first absorber's coefficients.
layout(local_size_x = 1) in;

#include "atmosphere_common.glsl"

/// The test's output (VALUES_BINDING, defined by the test).
layout(std430, binding = VALUES_BINDING) writeonly buffer Values { real values[]; };

void main() {
  values[0] = PI;
  values[1] = INV_4PI;
  values[2] = PENNDORF_A;
  values[3] = PENNDORF_B;
  values[4] = SERIES_LIMIT;
  const int fields[8] = int[8](FIELD_RAYLEIGH_SCATTERING, FIELD_MIE_SCATTERING, FIELD_MIE_EXTINCTION, FIELD_MIE_G1,
                               FIELD_MIE_G2, FIELD_MIE_ALPHA, FIELD_GROUND_ALBEDO, FIELD_ABSORBERS);
  const int named = ABSORBER_COUNT > 0 ? 8 : 7;
  for (int f = 0; f < named; ++f) {
    const real4 w = wavelength_field(fields[f]);
    for (int k = 0; k < 4; ++k) values[8 + 4 * f + k] = w[k];
  }
}
