// The filter kernel on a CUDA GPU (docs/gpu.md). One thread per output pixel, blocks of
// 32 × 8: a warp is 32 consecutive pixels of one row, so every thread of a warp walks the
// same window row with the same half width, and the only divergence is which taps pass.
//
// The block walks its window one absolute row at a time. Each row's span (the block's 32
// columns plus the radius on either side) is staged in shared memory for every plane the
// taps read, then every thread whose window holds that row takes its taps from there. So
// each plane value is read from device memory once per block row instead of once per tap,
// and a thread's taps come in a fixed order (window rows, then dx ascending): the sums do
// not depend on scheduling, and the output is the same run to run.
//
// The planes are the host layout's (filter_layout.h), copied as one block: thresholds,
// firefly levels and scaled guides are the CPU's floats, and the test is the AVX2/AVX-512
// kernels' fmaf(d, d, −T_j) ≤ T_i, so every membership decision is theirs. (The portable
// scalar kernel rounds d² before subtracting, and can differ at exact ties.)
#include <algorithm>
#include <cstddef>
#include <mutex>
#include <stdexcept>
#include <string>

#include <cuda_runtime.h>

#include "filter_cuda.h"
#include "statmc/core/cuda_device.h"

namespace statmc {

namespace {

void check(cudaError_t status, const char* what)
{
    if (status != cudaSuccess)
        throw std::runtime_error(std::string("CUDA: ") + what +
                                 " failed: " + cudaGetErrorString(status) + " (" +
                                 cudaGetErrorName(status) + ")");
}

/// Device memory that frees itself.
template <class T>
class DeviceBuffer {
public:
    DeviceBuffer() = default;
    DeviceBuffer(std::size_t count, const char* what)
    {
        if (count > 0)
            check(cudaMalloc(&data_, count * sizeof(T)), what);
    }
    ~DeviceBuffer()
    {
        if (data_)
            cudaFree(data_);
    }
    DeviceBuffer(DeviceBuffer&& other) noexcept : data_(other.data_) { other.data_ = nullptr; }
    DeviceBuffer& operator=(DeviceBuffer&& other) noexcept
    {
        std::swap(data_, other.data_);
        return *this;
    }
    T* get() const { return data_; }

private:
    T* data_ = nullptr;
};

template <class T>
DeviceBuffer<T> upload(const T* host, std::size_t count, const char* what)
{
    DeviceBuffer<T> buffer(count, what);
    if (count > 0)
        check(cudaMemcpy(buffer.get(), host, count * sizeof(T), cudaMemcpyHostToDevice), what);
    return buffer;
}

constexpr int kBlockX = 32, kBlockY = 8;

struct KernelParams {
    int width, height, pad_x, pad_y, reach_y;
    long long stride;  // floats per padded row
    // Pixel (0, 0) of each padded plane; null where the layout has none.
    const float* mean[4];
    const float* threshold[4];
    const float* value[4];
    const float* guide[6];
    const float* guide_noise;  // u per pixel, with guides (filter_layout.h)
    const float* noise;
    const float* noise_limit;
    const float* noise_own;
    const float* noise_mutual;
    const float* inverse_count;  // present with diagnostics
    const int* half_width;       // the window (set_window), index dy + pad_y
    const int* inner_half_width;
    const float* spatial;  // [(dy + pad_y)(2 pad_x + 1) + dx + pad_x]
    const float* spatial_log2;
    // Dense outputs, width floats per row.
    float* out[4];
    float* members;
    float* weight_sum;
    float* effective;
    float* carry[7];  // Σ W(F_j − F_i) per channel, Σ W, members, Σ W²/n; null: no carry
    int carry_from_previous;
};

/// Planes staged per window row: mean, threshold and value per channel, the guides, and
/// the guides' noise u, the firefly level and mutual limit, and 1/n where present.
int staged_planes(int channels, int guides, bool guide_noise, bool guard, bool inverse)
{
    return 3 * channels + guides + (guide_noise ? 1 : 0) + (guard ? 2 : 0) + (inverse ? 1 : 0);
}

template <int NC, int NG>
__global__ void __launch_bounds__(kBlockX* kBlockY) filter_kernel(const KernelParams p)
{
    extern __shared__ float staged[];
    const bool guard = p.noise != nullptr;
    const bool guide_noise = NG > 0 && p.guide_noise != nullptr;
    const bool diagnostics = p.inverse_count != nullptr;
    const int span = kBlockX + 2 * p.pad_x;
    float* s_mean = staged;
    float* s_threshold = s_mean + NC * span;
    float* s_value = s_threshold + NC * span;
    float* s_guide = s_value + NC * span;
    float* s_guide_noise = s_guide + NG * span;
    float* s_noise = s_guide_noise + (guide_noise ? span : 0);
    float* s_limit = s_noise + (guard ? span : 0);
    float* s_inverse = s_limit + (guard ? span : 0);

    const int x0 = blockIdx.x * kBlockX, y0 = blockIdx.y * kBlockY;
    const int x = x0 + threadIdx.x, y = y0 + threadIdx.y;
    const bool inside = x < p.width && y < p.height;
    const long long centre = (long long)y * p.stride + x;
    const long long at = (long long)y * p.width + x;

    float mean_i[NC], threshold_i[NC], value_i[NC], guide_i[NG > 0 ? NG : 1];
    float guide_noise_i = 0, limit_i = 0, level_i = 0;
    float acc[NC], weight_sum = 1, member_count = 1, inverse_sum = 0;
    if (inside) {
        for (int c = 0; c < NC; ++c) {
            mean_i[c] = p.mean[c][centre];
            threshold_i[c] = p.threshold[c][centre];
            value_i[c] = p.value[c][centre];
            acc[c] = 0;
        }
        for (int g = 0; g < NG; ++g)
            guide_i[g] = p.guide[g][centre];
        if (guide_noise)
            guide_noise_i = p.guide_noise[centre];
        if (guard) {
            limit_i = p.noise_limit[centre];
            level_i = p.noise_own[centre];
        }
        if (diagnostics)
            inverse_sum = p.inverse_count[centre];
        if (p.carry_from_previous) {
            for (int c = 0; c < NC; ++c)
                acc[c] = p.carry[c][at];
            weight_sum = p.carry[4][at];
            member_count = p.carry[5][at];
            inverse_sum = p.carry[6][at];
        }
    }

    // Only what a centre inside the image reads is staged: columns up to width − 1 + pad_x
    // and rows up to height − 1 + reach_y, all inside the padded planes.
    const int first_col = x0 - p.pad_x;
    const int end_col = min(x0 + kBlockX + p.pad_x, p.width + p.pad_x);
    const int last_y = min(y0 + kBlockY, p.height) - 1;
    const int thread = threadIdx.y * kBlockX + threadIdx.x;
    const int cols = 2 * p.pad_x + 1;
    for (int wy = y0 - p.reach_y; wy <= last_y + p.reach_y; ++wy) {
        __syncthreads();  // every thread is done with the previous row
        const long long row = (long long)wy * p.stride;
        for (int k = thread; k < end_col - first_col; k += kBlockX * kBlockY) {
            const long long from = row + first_col + k;
            for (int c = 0; c < NC; ++c) {
                s_mean[c * span + k] = p.mean[c][from];
                s_threshold[c * span + k] = p.threshold[c][from];
                s_value[c * span + k] = p.value[c][from];
            }
            for (int g = 0; g < NG; ++g)
                s_guide[g * span + k] = p.guide[g][from];
            if (guide_noise)
                s_guide_noise[k] = p.guide_noise[from];
            if (guard) {
                s_noise[k] = p.noise[from];
                s_limit[k] = p.noise_mutual[from];
            }
            if (diagnostics)
                s_inverse[k] = p.inverse_count[from];
        }
        __syncthreads();
        const int dy = wy - y;
        if (!inside || dy < -p.reach_y || dy > p.reach_y)
            continue;
        const int hw = p.half_width[dy + p.pad_y];
        const int inner = p.inner_half_width[dy + p.pad_y];
        const int table_row = (dy + p.pad_y) * cols + p.pad_x;
        auto tap = [&](int dx) {
            const int k = threadIdx.x + p.pad_x + dx;
            // The mutual firefly guard (firefly_guard.h).
            bool member = !guard || (s_noise[k] <= limit_i && level_i <= s_limit[k]);
            for (int c = 0; c < NC; ++c) {
                const float d = mean_i[c] - s_mean[c * span + k];
                member = member && fmaf(d, d, -s_threshold[c * span + k]) <= threshold_i[c];
            }
            if (!member)
                return;
            float w;
            if (NG == 0) {
                w = p.spatial[table_row + dx];
            } else {
                // log2 w = spatial − Σ (Δg)², in two chains as on the CPU.
                constexpr int kHalf = (NG + 1) / 2;
                float near = p.spatial_log2[table_row + dx], far = 0;
                // __fmul_rn/__fsub_rn: rounded as on the CPU, never fused by the compiler.
                for (int g = 0; g < NG; ++g) {
                    const float d = guide_i[g] - s_guide[g * span + k];
                    if (g < kHalf)
                        near = fmaf(-d, d, near);
                    else
                        far = g == kHalf ? __fmul_rn(d, d) : fmaf(d, d, far);
                }
                float log2_weight = __fsub_rn(near, far);
                if (guide_noise) {  // less the guides' noise (both ways alike), never above
                                    // the spatial weight
                    const float shared = fminf(guide_noise_i, s_guide_noise[k]);
                    log2_weight = fminf(__fadd_rn(log2_weight, __fadd_rn(shared, shared)),
                                        p.spatial_log2[table_row + dx]);
                }
                w = exp2f(log2_weight);
            }
            for (int c = 0; c < NC; ++c)
                acc[c] = fmaf(w, s_value[c * span + k] - value_i[c], acc[c]);
            weight_sum += w;
            if (diagnostics) {
                member_count += 1;
                inverse_sum = fmaf(__fmul_rn(w, w), s_inverse[k], inverse_sum);
            }
        };
        for (int dx = -hw; dx <= min(-inner - 1, -1); ++dx)
            tap(dx);
        if (inner < 0 && hw >= 0)
            tap(0);
        for (int dx = max(inner + 1, 1); dx <= hw; ++dx)
            tap(dx);
    }
    if (!inside)
        return;
    for (int c = 0; c < NC; ++c)
        p.out[c][at] = value_i[c] + acc[c] / weight_sum;
    if (p.members)
        p.members[at] = member_count;
    if (p.weight_sum)
        p.weight_sum[at] = weight_sum;
    if (p.effective)
        p.effective[at] = inverse_sum > 0 ? weight_sum * weight_sum / inverse_sum : 0.f;
    if (p.carry[4]) {
        for (int c = 0; c < NC; ++c)
            p.carry[c][at] = acc[c];
        p.carry[4][at] = weight_sum;
        p.carry[5][at] = member_count;
        p.carry[6][at] = inverse_sum;
    }
}

template <int NC, int NG>
void launch(const KernelParams& params, dim3 grid, std::size_t shared_bytes)
{
    if (shared_bytes > 48 * 1024)
        check(cudaFuncSetAttribute(filter_kernel<NC, NG>,
                                   cudaFuncAttributeMaxDynamicSharedMemorySize, int(shared_bytes)),
              "raising the kernel's shared memory");
    filter_kernel<NC, NG><<<grid, dim3(kBlockX, kBlockY), shared_bytes>>>(params);
}

template <int NC>
void launch_guides(int guides, const KernelParams& params, dim3 grid, std::size_t shared_bytes)
{
    switch (guides) {
    case 0:
        return launch<NC, 0>(params, grid, shared_bytes);
    case 3:
        return launch<NC, 3>(params, grid, shared_bytes);
    default:
        return launch<NC, 6>(params, grid, shared_bytes);
    }
}

void launch_kernel(int channels, int guides, const KernelParams& params, dim3 grid,
                   std::size_t shared_bytes)
{
    switch (channels) {
    case 1:
        return launch_guides<1>(guides, params, grid, shared_bytes);
    case 2:
        return launch_guides<2>(guides, params, grid, shared_bytes);
    case 3:
        return launch_guides<3>(guides, params, grid, shared_bytes);
    default:
        return launch_guides<4>(guides, params, grid, shared_bytes);
    }
}

/// The driver's answer, asked once per process (the first call initialises the driver).
struct Presence {
    bool present = false;
    std::string why, description;
    std::size_t shared_per_block = 0;  ///< the most a block may opt in to
};

const Presence& presence()
{
    static Presence p;
    static std::once_flag once;
    std::call_once(once, [] {
        int count = 0;
        const cudaError_t status = cudaGetDeviceCount(&count);
        if (status != cudaSuccess) {
            cudaGetLastError();  // not sticky, but leave nothing behind
            const std::string runtime = std::to_string(CUDART_VERSION / 1000) + "." +
                                        std::to_string(CUDART_VERSION % 1000 / 10);
            if (status == cudaErrorNoDevice)
                p.why = "no CUDA device is present";
            else if (status == cudaErrorInsufficientDriver)
                p.why = "no NVIDIA driver for CUDA " + runtime +
                        " was found (none installed, or an older one)";
            else
                p.why = std::string("the CUDA driver cannot be used (") +
                        cudaGetErrorString(status) + ")";
            return;
        }
        if (count == 0) {
            p.why = "no CUDA device is present";
            return;
        }
        int device = 0;
        cudaDeviceProp prop{};
        if (cudaGetDevice(&device) != cudaSuccess ||
            cudaGetDeviceProperties(&prop, device) != cudaSuccess) {
            cudaGetLastError();
            p.why = "the CUDA device's properties cannot be read";
            return;
        }
        // The build carries sm_90 code and compute_75 PTX: nothing older can run it.
        if (prop.major * 10 + prop.minor < 75) {
            p.why = std::string(prop.name) + " has compute capability " +
                    std::to_string(prop.major) + "." + std::to_string(prop.minor) +
                    "; statmc's kernels need 7.5 (Turing) or later";
            return;
        }
        p.present = true;
        p.shared_per_block = prop.sharedMemPerBlockOptin;
        p.description = std::string(prop.name) + ", compute capability " +
                        std::to_string(prop.major) + "." + std::to_string(prop.minor) + ", " +
                        std::to_string(prop.multiProcessorCount) + " multiprocessors";
    });
    return p;
}

/// One CUDA event, destroyed with its owner. Blocking: a wait sleeps instead of spinning a
/// core for the length of the kernel.
class Event {
public:
    Event()
    {
        check(cudaEventCreateWithFlags(&event_, cudaEventBlockingSync), "creating an event");
    }
    ~Event() { cudaEventDestroy(event_); }
    Event(const Event&) = delete;
    Event& operator=(const Event&) = delete;
    cudaEvent_t get() const { return event_; }

private:
    cudaEvent_t event_{};
};

/// CUDA events around one stretch of work.
class EventTimer {
public:
    void start() { check(cudaEventRecord(start_.get()), "recording an event"); }
    float stop()
    {
        check(cudaEventRecord(stop_.get()), "recording an event");
        check(cudaEventSynchronize(stop_.get()), "waiting for the GPU");
        float ms = 0;
        check(cudaEventElapsedTime(&ms, start_.get(), stop_.get()), "reading an event");
        return ms;
    }

private:
    Event start_, stop_;
};

}  // namespace

bool built_with_cuda() { return true; }

bool cuda_available(std::string* why)
{
    const Presence& p = presence();
    if (!p.present && why)
        *why = p.why;
    return p.present;
}

std::string cuda_device_description() { return presence().description; }

namespace detail {

struct CudaFilter::Impl {
    int width = 0, height = 0, channels = 0, averaged = 0, guides = 0;
    std::size_t pixels = 0;
    bool guard = false, inverse = false;
    DeviceBuffer<float> planes, spatial, spatial_log2, out, diagnostics, carry;
    DeviceBuffer<int> half_width, inner_half_width;
    KernelParams params{};
    std::size_t shared_bytes = 0;
    std::vector<float> host;  // downloads land here before the strided planes
    EventTimer timer;
    CudaTimings timings;
};

CudaFilter::CudaFilter(const FilterLayout& L, bool carry)
{
    std::string why;
    if (!cuda_available(&why))
        throw std::runtime_error("CUDA: " + why);
    if (L.channels > 4)
        throw std::runtime_error("CUDA: the GPU kernel takes 1 to 4 channels, not the " +
                                 std::to_string(L.channels) +
                                 " of jointly tested AOVs; use device=cpu");
    impl_ = std::make_unique<Impl>();
    Impl& m = *impl_;
    m.width = L.width;
    m.height = L.height;
    m.channels = L.channels;
    m.averaged = L.averaged;
    m.guides = L.guide_count;
    m.pixels = std::size_t(L.width) * L.height;
    m.guard = L.noise != nullptr;
    m.inverse = L.inverse_count != nullptr;

    const int span = kBlockX + 2 * L.pad_x;
    m.shared_bytes = std::size_t(staged_planes(L.channels, L.guide_count, L.guide_noise != nullptr,
                                               m.guard, m.inverse)) *
                     span * sizeof(float);
    if (m.shared_bytes > presence().shared_per_block)
        throw std::runtime_error("CUDA: radius " + std::to_string(L.pad_x) + " needs " +
                                 std::to_string(m.shared_bytes / 1024) +
                                 " KB of shared memory per block, more than the GPU's " +
                                 std::to_string(presence().shared_per_block / 1024) +
                                 " KB; use device=cpu");

    m.timer.start();
    m.planes = upload(L.storage.get(), L.storage_floats, "copying the layout to the GPU");
    m.spatial = upload(L.spatial_weight.data(), L.spatial_weight.size(), "copying the weights");
    m.spatial_log2 =
        upload(L.spatial_log2_weight.data(), L.spatial_log2_weight.size(), "copying the weights");
    m.timings.upload_ms = m.timer.stop();
    m.half_width = DeviceBuffer<int>(L.half_width.size(), "allocating the window table");
    m.inner_half_width = DeviceBuffer<int>(L.half_width.size(), "allocating the window table");
    m.out = DeviceBuffer<float>(m.pixels * L.channels, "allocating the output");
    m.diagnostics = DeviceBuffer<float>(m.pixels * 3, "allocating the diagnostics");
    if (carry)
        m.carry = DeviceBuffer<float>(m.pixels * FilterLayout::kCarryPlanes,
                                      "allocating the ladder's sums");

    KernelParams& p = m.params;
    p.width = L.width;
    p.height = L.height;
    p.pad_x = L.pad_x;
    p.pad_y = L.pad_y;
    p.stride = L.stride;
    const float* host_block = L.storage.get();
    auto on_device = [&](const float* host) -> const float* {
        return host ? m.planes.get() + (host - host_block) : nullptr;
    };
    for (int c = 0; c < L.channels; ++c) {
        p.mean[c] = on_device(L.mean[c]);
        p.threshold[c] = on_device(L.threshold[c]);
        p.value[c] = on_device(L.value[c]);
        p.out[c] = m.out.get() + c * m.pixels;
    }
    for (int g = 0; g < L.guide_count; ++g)
        p.guide[g] = on_device(L.guide[g]);
    p.guide_noise = L.guide_noise ? on_device(L.guide_noise) : nullptr;
    p.noise = on_device(L.noise);
    p.noise_limit = on_device(L.noise_limit);
    p.noise_own = on_device(L.noise_own);
    p.noise_mutual = on_device(L.noise_mutual);
    p.inverse_count = on_device(L.inverse_count);
    p.half_width = m.half_width.get();
    p.inner_half_width = m.inner_half_width.get();
    p.spatial = m.spatial.get();
    p.spatial_log2 = m.spatial_log2.get();
    if (carry)
        for (int k = 0; k < FilterLayout::kCarryPlanes; ++k)
            p.carry[k] = m.carry.get() + k * m.pixels;
}

CudaFilter::~CudaFilter() = default;

void CudaFilter::run(const FilterLayout& L, const std::vector<Plane>& out,
                     const FilterDiagnostics& diagnostics)
{
    Impl& m = *impl_;
    KernelParams p = m.params;
    p.reach_y = L.reach_y;
    p.carry_from_previous = L.carry_from_previous && p.carry[4] != nullptr;
    check(cudaMemcpy(m.half_width.get(), L.half_width.data(), L.half_width.size() * sizeof(int),
                     cudaMemcpyHostToDevice),
          "copying the window table");
    check(cudaMemcpy(m.inner_half_width.get(), L.inner_half_width.data(),
                     L.inner_half_width.size() * sizeof(int), cudaMemcpyHostToDevice),
          "copying the window table");
    float* diag = m.diagnostics.get();
    p.members = diagnostics.members ? diag : nullptr;
    p.weight_sum = diagnostics.weight_sum ? diag + m.pixels : nullptr;
    p.effective = diagnostics.effective_samples ? diag + 2 * m.pixels : nullptr;

    const dim3 grid((m.width + kBlockX - 1) / kBlockX, (m.height + kBlockY - 1) / kBlockY);
    cudaGetLastError();  // an error left by earlier CUDA work is not this launch's
    m.timer.start();
    launch_kernel(m.channels, m.guides, p, grid, m.shared_bytes);
    check(cudaGetLastError(), "launching the filter kernel");
    m.timings.kernel_ms = m.timer.stop();

    m.timer.start();
    m.host.resize(m.pixels * (m.channels + 3));
    check(cudaMemcpy(m.host.data(), m.out.get(), m.pixels * m.channels * sizeof(float),
                     cudaMemcpyDeviceToHost),
          "copying the output from the GPU");
    if (diagnostics.any())
        check(cudaMemcpy(m.host.data() + m.pixels * m.channels, diag, m.pixels * 3 * sizeof(float),
                         cudaMemcpyDeviceToHost),
              "copying the diagnostics from the GPU");
    m.timings.download_ms = m.timer.stop();

    auto scatter = [&](const float* dense, const Plane& plane) {
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x)
                plane(x, y) = dense[std::size_t(y) * m.width + x];
    };
    for (int c = 0; c < m.averaged; ++c)  // context channels are tested, not written
        scatter(m.host.data() + c * m.pixels, out[c]);
    const float* diag_host = m.host.data() + m.pixels * m.channels;
    if (diagnostics.members)
        scatter(diag_host, diagnostics.members);
    if (diagnostics.weight_sum)
        scatter(diag_host + m.pixels, diagnostics.weight_sum);
    if (diagnostics.effective_samples)
        scatter(diag_host + 2 * m.pixels, diagnostics.effective_samples);
}

CudaTimings CudaFilter::timings() const { return impl_->timings; }

}  // namespace detail
}  // namespace statmc
