// The arccos lookup table of the form-factor shader (paper 002 §3.1), and a CPU model of
// its lookup so that its error can be measured without a GPU.
#pragma once

#include <vector>

namespace hemirad::gpu {

constexpr int kAcosTableSize = 2048;

/// Entry i holds acos(1 - s_i^2), s_i = i/(N-1): the table is uniform in s = sqrt(1 - x),
/// which concentrates entries near x = 1 (small angles, far receivers).
std::vector<float> make_acos_table(int size = kAcosTableSize);

/// The shader's lookup (hemicube.frag, table_angle) in float, for error measurement: the
/// angle between unit vectors a and b, indexed by the chord |a -+ b| / sqrt(2).
float table_angle(const std::vector<float>& table, const float a[3], const float b[3]);

} // namespace hemirad::gpu
