#include "statmc/layers/imagebufalgo_forms.h"

#include <OpenImageIO/imageio.h>

namespace statmc::layers {

int thread_count(int nthreads)
{
    if (nthreads > 0)
        return nthreads;
    int global = 0;
    OIIO::getattribute("threads", global);
    return global > 0 ? global : 0;
}

}  // namespace statmc::layers
