// A ray: where it starts and where it goes.
#pragma once

#include "statmc/render/vec.h"

namespace statmc::render {

struct Ray {
    Vec3 origin;
    Vec3 direction;  ///< unit length
};

}  // namespace statmc::render
