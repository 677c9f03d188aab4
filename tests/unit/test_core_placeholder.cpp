#include <catch2/catch.hpp>
#include "icgp/geometry/pose.h"
TEST_CASE("placeholder") { CHECK(icgp::Pose().matrix().isIdentity()); }
