// CUDA-OpenGL interop: the renderer's two vertex buffers registered with CUDA, mapped each frame,
// filled by one kernel from the simulation's packed device arrays (position, velocity with density
// in w), unmapped for drawing.
// cuda_gl_interop.h brings its own GL header; this file uses no GL call, only buffer names.
#include <cuda_gl_interop.h>

#include "core/exec_cuda.cuh"
#include "physics/eos.h"
#include "render/gl_cuda_device.h"
#include "render/particle_interop.h"
#include "solver/simulation.h"

namespace weir {

namespace {

constexpr int kDeviceSpeed = 0, kDeviceDensity = 1, kDevicePressure = 2;

__global__ void fillParticleBuffers(const Real4* pos, const Real4* vel, Index n, SphParams params,
                                    int field, float* positions, float* values) {
    const Index i = Index(blockIdx.x) * Index(blockDim.x) + Index(threadIdx.x);
    if (i >= n) {
        return;
    }
    const Real4 p = pos[i], v = vel[i];
    positions[3 * i] = float(p.x);
    positions[3 * i + 1] = float(p.y);
    positions[3 * i + 2] = float(p.z);
    float value = 0;
    if (field == kDeviceSpeed) {
        value = float(sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z));
    } else if (field == kDeviceDensity) {
        value = float(v.w);
    } else {
        value = float(pressureFromDensity(params, v.w));
    }
    values[i] = value;
}

// The colour fields the kernel computes from the solver's packed arrays; any other field of the
// registry is drawn from a host copy.
int deviceFieldCode(ColourField field) {
    if (field == ColourField::Speed) {
        return kDeviceSpeed;
    }
    if (field == ColourField::Density) {
        return kDeviceDensity;
    }
    if (field == ColourField::Pressure) {
        return kDevicePressure;
    }
    return -1;
}

class CudaParticleInterop : public ParticleInterop {
   public:
    explicit CudaParticleInterop(Simulation& simulation) : simulation_(simulation) {}
    ~CudaParticleInterop() override { unregister(); }

    void update(Renderer& renderer, ColourField field, double radius) override {
        const int code = deviceFieldCode(field);
        if (code < 0) {
            simulation_.download(host_);
            renderer.setParticles(host_, field, radius);
            return;
        }
        const ParticleArrays arrays = simulation_.particleArrays();
        const Index n = arrays.count;
        const auto [positionBuffer, valueBuffer] = renderer.reserveParticleBuffers(std::size_t(n));
        if (positionBuffer != positionBuffer_ || valueBuffer != valueBuffer_ || n != registered_) {
            unregister();
            WEIR_CUDA_CHECK(cudaGraphicsGLRegisterBuffer(&resources_[0], positionBuffer,
                                                         cudaGraphicsRegisterFlagsWriteDiscard));
            WEIR_CUDA_CHECK(cudaGraphicsGLRegisterBuffer(&resources_[1], valueBuffer,
                                                         cudaGraphicsRegisterFlagsWriteDiscard));
            positionBuffer_ = positionBuffer;
            valueBuffer_ = valueBuffer;
            registered_ = n;
        }
        WEIR_CUDA_CHECK(cudaGraphicsMapResources(2, resources_, 0));
        float* positions = nullptr;
        float* values = nullptr;
        std::size_t bytes = 0;
        WEIR_CUDA_CHECK(cudaGraphicsResourceGetMappedPointer(reinterpret_cast<void**>(&positions),
                                                             &bytes, resources_[0]));
        WEIR_CUDA_CHECK(cudaGraphicsResourceGetMappedPointer(reinterpret_cast<void**>(&values),
                                                             &bytes, resources_[1]));
        if (n > 0) {
            const int block = 256;
            fillParticleBuffers<<<unsigned((n + block - 1) / block), block>>>(
                arrays.pos, arrays.vel, n, simulation_.params(), code, positions, values);
            WEIR_CUDA_CHECK(cudaGetLastError());
        }
        WEIR_CUDA_CHECK(cudaGraphicsUnmapResources(2, resources_, 0));
        renderer.setFilledParticles(std::size_t(n), field, radius);
    }

    std::string description() const override { return "CUDA-OpenGL interop"; }

   private:
    void unregister() {
        for (cudaGraphicsResource*& r : resources_) {
            if (r != nullptr) {
                cudaGraphicsUnregisterResource(r);
                r = nullptr;
            }
        }
        registered_ = -1;
    }

    Simulation& simulation_;
    HostParticles host_;  // for fields the kernel does not compute
    cudaGraphicsResource* resources_[2] = {nullptr, nullptr};
    unsigned positionBuffer_ = 0, valueBuffer_ = 0;
    Index registered_ = -1;
};

}  // namespace

std::unique_ptr<ParticleInterop> makeParticleInterop(Simulation& simulation, std::string* why) {
    auto say = [&](const std::string& reason) {
        if (why != nullptr) {
            *why = reason;
        }
        return nullptr;
    };
    if (!simulation.particleArrays().onDevice) {
        return say("the simulation runs on the CPU");
    }
    std::string reason;
    if (!openGlRunsOnCurrentCudaDevice(reason)) {
        return say(reason);
    }
    return std::make_unique<CudaParticleInterop>(simulation);
}

bool openGlRunsOnCurrentCudaDevice(std::string& why) {
    // The CUDA devices behind the current OpenGL context: none for Mesa's software renderer.
    unsigned int count = 0;
    int devices[8] = {};
    if (cudaGLGetDevices(&count, devices, 8, cudaGLDeviceListAll) != cudaSuccess || count == 0) {
        cudaGetLastError();  // the failed query leaves its error for the next check: clear it
        why = "the window's OpenGL does not run on a CUDA device";
        return false;
    }
    int current = -1;
    WEIR_CUDA_CHECK(cudaGetDevice(&current));
    for (unsigned int k = 0; k < count; ++k) {
        if (devices[k] == current) {
            return true;
        }
    }
    why = "the window's OpenGL runs on another GPU than the simulation";
    return false;
}

}  // namespace weir
