#include <doctest/doctest.h>
#include "system.hpp"
TEST_CASE("empty") { particles::SystemBuilder b; auto s = b.build(); CHECK(s.state().size() == 0); }
