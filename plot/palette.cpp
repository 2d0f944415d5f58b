#include "plot/palette.hpp"

#include <array>

namespace particles::plot {

Rgb seriesColour(std::size_t index) {
  static constexpr std::array<unsigned, 10> kTableau10 = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd,
                                                          0x8c564b, 0xe377c2, 0x7f7f7f, 0xbcbd22, 0x17becf};
  const unsigned c = kTableau10[index % kTableau10.size()];
  return {((c >> 16) & 0xff) / 255.0, ((c >> 8) & 0xff) / 255.0, (c & 0xff) / 255.0};
}

}  // namespace particles::plot
