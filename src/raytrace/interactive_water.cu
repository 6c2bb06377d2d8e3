// The live water look on CUDA (interactive_water.h): surface, hierarchy, paths and tone mapping,
// every stage on the GPU, on one stream; the host reads back only counts and bounds.
#include <cuda_runtime.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/backend.h"
#include "raytrace/interactive_water.h"
#include "raytrace/lbvh_cuda.cuh"
#include "raytrace/surface_triangles.h"
#include "raytrace/tone_map.h"
#include "surface/surface_pipeline.h"

namespace weir {

// Instantiated in surface/surface_cuda.cu.
extern template std::int64_t extractSurfaceInto<CudaExec>(CudaExec&, const Real4*, Index,
                                                          const SurfacePlan&, const char*,
                                                          BackendMesh<CudaExec>&, StageTimes*);

namespace {

// 16 x 8 pixels per block, as the offline tracer: neighbouring rays walk the same nodes.
__global__ void accumulatePathsKernel(TracingSceneView scene, WaterLook look, PinholeCamera camera,
                                      int width, int height, int firstSample, int samples,
                                      Vec3f* sum) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) {
        return;
    }
    const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
    const Vec3f mean = tracePixel(scene, look, camera, width, height, x, y, samples, firstSample);
    sum[i] = (firstSample == 0 ? Vec3f() : sum[i]) + mean * float(samples);
}

__global__ void toneMapKernel(const Vec3f* sum, std::size_t pixels, float inversePaths,
                              float exposure, std::uint8_t* rgba) {
    const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i >= pixels) {
        return;
    }
    const Vec3f mean = sum[i] * inversePaths;
    const uchar4 pixel{toneMapToByte(mean.x, exposure), toneMapToByte(mean.y, exposure),
                       toneMapToByte(mean.z, exposure), 255};
    reinterpret_cast<uchar4*>(rgba)[i] = pixel;
}

// The particles' bounds into lohi (6 ints, lbvh_cuda.cuh), rounded outwards to floats. (The
// device lambdas live in free functions: nvcc does not allow them in a private nested class.)
void reduceParticleBounds(cudaStream_t stream, const Real4* pos, Index n, int* lohi) {
    reduceBounds(
        stream, n,
        [=] __device__(Index i, Vec3f & lo, Vec3f & hi) {
            const Real4 p = pos[i];
#if defined(WEIR_DOUBLE)
            lo = Vec3f(__double2float_rd(p.x), __double2float_rd(p.y), __double2float_rd(p.z));
            hi = Vec3f(__double2float_ru(p.x), __double2float_ru(p.y), __double2float_ru(p.z));
#else
            lo = hi = Vec3f(p.x, p.y, p.z);
#endif
        },
        lohi);
}

// keptEnd[i]: 1 where surface triangle i is kept, else 0 (a prefix sum follows).
void markKeptTriangles(CudaExec& exec, const SurfaceMeshView& view, const ContactRule& rule,
                       Index t, Index* keptEnd) {
    exec.forEach(t, [=] __device__(Index i) {
        BvhTriangle tri;
        TriangleShading shade;
        keptEnd[i] = keptSurfaceTriangle(view, i, rule, tri, shade) ? 1 : 0;
    });
}

// The kept triangles written to their slots (keptEnd now the inclusive prefix sum).
void writeKeptTriangles(CudaExec& exec, const SurfaceMeshView& view, const ContactRule& rule,
                        Index t, const Index* keptEnd, BvhTriangle* triangleOut,
                        TriangleShading* shadingOut) {
    exec.forEach(t, [=] __device__(Index i) {
        BvhTriangle tri;
        TriangleShading shade;
        if (keptSurfaceTriangle(view, i, rule, tri, shade)) {
            triangleOut[keptEnd[i] - 1] = tri;
            shadingOut[keptEnd[i] - 1] = shade;
        }
    });
}

float eventMs(cudaEvent_t from, cudaEvent_t to) {
    float ms = 0;
    WEIR_CUDA_CHECK(cudaEventElapsedTime(&ms, from, to));
    return ms;
}

bool samePoses(const std::vector<BodyPose>& a, const std::vector<BodyPose>& b) {
    if (a.size() != b.size()) {
        return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (!(a[i].position.x == b[i].position.x && a[i].position.y == b[i].position.y &&
              a[i].position.z == b[i].position.z) ||
            std::memcmp(a[i].orientation, b[i].orientation, sizeof a[i].orientation) != 0) {
            return false;
        }
    }
    return true;
}

bool sameCamera(const PinholeCamera& a, const PinholeCamera& b) {
    const auto same = [](const Vec3f& p, const Vec3f& q) {
        return p.x == q.x && p.y == q.y && p.z == q.z;
    };
    return same(a.eye, b.eye) && same(a.forward, b.forward) && same(a.right, b.right) &&
           same(a.up, b.up) && a.tanHalfFovY == b.tanHalfFovY && a.aspect == b.aspect;
}

}  // namespace

struct InteractiveWater::Impl {
    enum { kStart, kSurface, kHierarchy, kTrace, kToneMap, kEvents };

    explicit Impl(const InteractiveWaterSetup& s) : setup(s) {
        if (!(setup.surface.spacing > 0)) {
            throw std::invalid_argument("the live water look needs the particle spacing");
        }
        if (setup.pathsPerFrame < 1 || setup.pathsPerFrame > 65536) {
            throw std::invalid_argument("the live water look's paths per frame is " +
                                        std::to_string(setup.pathsPerFrame) +
                                        ", must be within 1..65536");
        }
        for (cudaEvent_t& e : events) {
            WEIR_CUDA_CHECK(cudaEventCreate(&e));
        }
        const Box& box = setup.scene.container;
        base.containerLo = Vec3f(box.min);
        base.containerHi = Vec3f(box.max);
        base.rayEpsilon = float(std::max(1e-6, 2e-5 * length(box.max - box.min)));
        setMatte({});
        resize(setup.width, setup.height);
    }
    ~Impl() {
        for (cudaEvent_t e : events) {
            cudaEventDestroy(e);
        }
    }

    // The obstacles and the bodies at these poses: the offline scene's triangles without water.
    void setMatte(const std::vector<BodyPose>& bodyPoses) {
        TracingSceneDescription d = setup.scene;
        d.water = nullptr;
        d.bodyPoses = bodyPoses;
        const TracingScene matte(d);
        exec.upload(matteTriangles, matte.bvh().triangles().data(), matte.bvh().triangles().size());
        exec.upload(matteShading, matte.shading().data(), matte.shading().size());
        matteCount = Index(matte.shading().size());
        poses = bodyPoses;
        trianglesDirty = true;
    }

    void resize(int w, int h) {
        if (w < 1 || h < 1 || w > 16384 || h > 16384) {
            throw std::invalid_argument("live water image of " + std::to_string(w) + " x " +
                                        std::to_string(h) + " pixels: each must be 1..16384");
        }
        width = w;
        height = h;
        const std::size_t pixels = std::size_t(w) * std::size_t(h);
        accumulation.resize(pixels);
        rgba.resize(4 * pixels);
        WEIR_CUDA_CHECK(cudaMemsetAsync(rgba.data(), 0, 4 * pixels, exec.stream()));
        camera.aspect = float(w) / float(h);
        paths = 0;
    }

    // Particle bounds on the GPU (read back: the plan sizes the lattice on the host), the plan,
    // then the surface into `mesh`.
    void extractSurface() {
        reduceParticleBounds(exec.stream(), particles, particleCount, bounds.data());
        int lohi[6];
        exec.copyToHost(lohi, bounds.data(), sizeof lohi);
        const Vec3d lo(floatOfOrderedBits(lohi[0]), floatOfOrderedBits(lohi[1]),
                       floatOfOrderedBits(lohi[2]));
        const Vec3d hi(floatOfOrderedBits(lohi[3]), floatOfOrderedBits(lohi[4]),
                       floatOfOrderedBits(lohi[5]));
        const SurfacePlan plan = planSurfaceForBounds(lo, hi, setup.surface);
        extractSurfaceInto(exec, particles, particleCount, plan, "the GPU", mesh,
                           setup.timeSurfaceStages ? &surfaceStages : nullptr);
    }

    // The surface's kept faces (compacted by a prefix sum), the matte triangles after them, the
    // hierarchy over all.
    void buildHierarchy() {
        const std::int64_t surfaceTriangles = hasWater ? mesh.triangleCount : 0;
        if (surfaceTriangles + matteCount >= (std::int64_t(1) << 30)) {
            throw std::runtime_error(
                "the live water look's hierarchy holds up to 2^30 triangles; "
                "the surface has " +
                std::to_string(surfaceTriangles));
        }
        const Index t = Index(surfaceTriangles);
        Index kept = 0;
        triangles.resize(std::size_t(t) + std::size_t(matteCount) + 1);
        shading.resize(std::size_t(t) + std::size_t(matteCount) + 1);
        if (t > 0) {
            keptEnd.resize(std::size_t(t));
            const SurfaceMeshView view{mesh.positions.data(), mesh.normals.data(),
                                       mesh.indices.data()};
            const Box& box = setup.scene.container;
            const ContactRule rule{box.min, box.max, walls, setup.scene.contactDistance};
            markKeptTriangles(exec, view, rule, t, keptEnd.data());
            exec.inclusiveScan(keptEnd.data(), keptEnd.data(), t);
            kept = exec.readOne(keptEnd, std::size_t(t - 1));
            writeKeptTriangles(exec, view, rule, t, keptEnd.data(), triangles.data(),
                               shading.data());
        }
        if (matteCount > 0) {
            WEIR_CUDA_CHECK(cudaMemcpyAsync(triangles.data() + kept, matteTriangles.data(),
                                            std::size_t(matteCount) * sizeof(BvhTriangle),
                                            cudaMemcpyDeviceToDevice, exec.stream()));
            WEIR_CUDA_CHECK(cudaMemcpyAsync(shading.data() + kept, matteShading.data(),
                                            std::size_t(matteCount) * sizeof(TriangleShading),
                                            cudaMemcpyDeviceToDevice, exec.stream()));
        }
        lbvh.build(exec, triangles.data(), shading.data(), kept + matteCount);
        times.triangles = kept + matteCount;
    }

    void render() {
        WEIR_CUDA_CHECK(cudaEventRecord(events[kStart], exec.stream()));
        const bool rebuildSurface = surfaceDirty && particles != nullptr && particleCount > 0;
        if (rebuildSurface) {
            extractSurface();
            hasWater = true;
            trianglesDirty = true;
        } else if (surfaceDirty) {
            hasWater = false;  // no particles
            trianglesDirty = true;
        }
        surfaceDirty = false;
        WEIR_CUDA_CHECK(cudaEventRecord(events[kSurface], exec.stream()));
        const bool rebuildHierarchy = trianglesDirty;
        if (trianglesDirty) {
            buildHierarchy();
            trianglesDirty = false;
            paths = 0;
        }
        WEIR_CUDA_CHECK(cudaEventRecord(events[kHierarchy], exec.stream()));

        TracingSceneView scene = base;
        scene.bvh = lbvh.view();
        scene.shading = lbvh.shading();
        scene.walls = walls;
        const dim3 block(16, 8);
        const dim3 grid(unsigned((width + 15) / 16), unsigned((height + 7) / 8));
        const int samples = setup.pathsPerFrame;
        if (paths > (1 << 30) - samples) {
            paths = 0;  // the sample counter would overflow: start again
        }
        accumulatePathsKernel<<<grid, block, 0, exec.stream()>>>(
            scene, setup.look, camera, width, height, paths, samples, accumulation.data());
        WEIR_CUDA_CHECK(cudaGetLastError());
        paths += samples;
        times.paths = samples;
        WEIR_CUDA_CHECK(cudaEventRecord(events[kTrace], exec.stream()));

        const std::size_t pixels = std::size_t(width) * std::size_t(height);
        toneMapKernel<<<unsigned((pixels + 255) / 256), 256, 0, exec.stream()>>>(
            accumulation.data(), pixels, 1.0f / float(paths), setup.look.exposure, rgba.data());
        WEIR_CUDA_CHECK(cudaGetLastError());
        WEIR_CUDA_CHECK(cudaEventRecord(events[kToneMap], exec.stream()));
        WEIR_CUDA_CHECK(cudaEventSynchronize(events[kToneMap]));
        times.surfaceMs = rebuildSurface ? eventMs(events[kStart], events[kSurface]) : 0;
        times.bvhMs = rebuildHierarchy ? eventMs(events[kSurface], events[kHierarchy]) : 0;
        times.traceMs = eventMs(events[kHierarchy], events[kTrace]);
        times.toneMapMs = eventMs(events[kTrace], events[kToneMap]);
    }

    InteractiveWaterSetup setup;
    CudaExec exec;
    cudaEvent_t events[kEvents] = {};
    InteractiveWaterTimes times;
    StageTimes surfaceStages;

    // The fluid: particles (not owned) and the surface built from them, or a mesh given.
    const Real4* particles = nullptr;
    Index particleCount = 0;
    DeviceBuffer<Real4> hostParticles;  // setHostParticles's copy
    DeviceBuffer<int> bounds{6};
    BackendMesh<CudaExec> mesh;
    bool hasWater = false, surfaceDirty = false, trianglesDirty = true;

    // The obstacles and bodies, and the triangles the hierarchy is built over.
    DeviceBuffer<BvhTriangle> matteTriangles, triangles;
    DeviceBuffer<TriangleShading> matteShading, shading;
    Index matteCount = 0;
    std::vector<BodyPose> poses;
    DeviceBuffer<Index> keptEnd;
    DeviceLbvh lbvh;

    // The image.
    TracingSceneView base;
    std::uint32_t walls = 0;
    PinholeCamera camera;
    bool cameraSet = false;
    int width = 0, height = 0, paths = 0;
    DeviceBuffer<Vec3f> accumulation;
    DeviceBuffer<std::uint8_t> rgba;
};

InteractiveWater::InteractiveWater(const InteractiveWaterSetup& setup) {
    if (!cudaDeviceAvailable()) {
        throw std::runtime_error("the live water look needs a CUDA device; none is visible");
    }
    impl_ = std::make_unique<Impl>(setup);
}

InteractiveWater::~InteractiveWater() = default;

void InteractiveWater::setParticles(const Real4* devicePositions, Index n) {
    impl_->particles = devicePositions;
    impl_->particleCount = n;
    impl_->surfaceDirty = true;
}

void InteractiveWater::setHostParticles(const HostParticles& particles) {
    Impl& m = *impl_;
    std::vector<Real4> packed(particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i) {
        packed[i] = {particles.x[i], particles.y[i], particles.z[i], Real(0)};
    }
    m.exec.upload(m.hostParticles, packed.data(), packed.size());
    setParticles(m.hostParticles.data(), Index(packed.size()));
}

void InteractiveWater::setMesh(const TriangleMesh& mesh) {
    Impl& m = *impl_;
    m.exec.upload(m.mesh.positions, mesh.positions.data(), mesh.positions.size());
    if (mesh.normals.size() == mesh.positions.size()) {
        m.exec.upload(m.mesh.normals, mesh.normals.data(), mesh.normals.size());
    } else {  // no vertex normals: zeros, which become the face normals
        const std::vector<Vec3f> zeros(mesh.positions.size());
        m.exec.upload(m.mesh.normals, zeros.data(), zeros.size());
    }
    m.exec.upload(m.mesh.indices, mesh.indices.data(), mesh.indices.size());
    m.mesh.vertexCount = std::int64_t(mesh.positions.size());
    m.mesh.triangleCount = std::int64_t(mesh.triangleCount());
    m.particles = nullptr;
    m.surfaceDirty = false;
    m.hasWater = true;
    m.trianglesDirty = true;
}

void InteractiveWater::setBodyPoses(const std::vector<BodyPose>& poses) {
    if (!impl_->setup.scene.bodies.empty() && !samePoses(poses, impl_->poses)) {
        impl_->setMatte(poses);
    }
}

void InteractiveWater::setCamera(const PinholeCamera& camera) {
    Impl& m = *impl_;
    PinholeCamera c = camera;
    c.aspect = float(m.width) / float(m.height);
    if (m.cameraSet && sameCamera(c, m.camera)) {
        return;
    }
    m.camera = c;
    m.cameraSet = true;
    m.paths = 0;
    const std::uint32_t walls = wallsSeenFrom(m.setup.scene.container, Vec3d(camera.eye));
    if (walls != m.walls) {
        m.walls = walls;
        m.trianglesDirty = true;  // the faces on the walls that are there are left out
    }
}

void InteractiveWater::resize(int width, int height) {
    if (width != impl_->width || height != impl_->height) {
        impl_->resize(width, height);
    }
}

void InteractiveWater::setPathsPerFrame(int paths) {
    if (paths < 1 || paths > 65536) {
        throw std::invalid_argument("the live water look's paths per frame is " +
                                    std::to_string(paths) + ", must be within 1..65536");
    }
    impl_->setup.pathsPerFrame = paths;
}

void InteractiveWater::render() { impl_->render(); }

int InteractiveWater::width() const { return impl_->width; }
int InteractiveWater::height() const { return impl_->height; }
int InteractiveWater::pathsPerPixel() const { return impl_->paths; }
const InteractiveWaterTimes& InteractiveWater::times() const { return impl_->times; }
const StageTimes& InteractiveWater::surfaceStages() const { return impl_->surfaceStages; }
const std::uint8_t* InteractiveWater::deviceRgba() const { return impl_->rgba.data(); }

std::vector<Vec3f> InteractiveWater::radiance() const {
    Impl& m = *impl_;
    std::vector<Vec3f> image(std::size_t(m.width) * std::size_t(m.height));
    m.exec.copyToHost(image.data(), m.accumulation.data(), image.size() * sizeof(Vec3f));
    const float scale = m.paths > 0 ? 1.0f / float(m.paths) : 0.0f;
    for (Vec3f& p : image) {
        p = p * scale;
    }
    return image;
}

std::vector<std::uint8_t> InteractiveWater::rgb() const {
    Impl& m = *impl_;
    const std::size_t pixels = std::size_t(m.width) * std::size_t(m.height);
    std::vector<std::uint8_t> rgba(4 * pixels), out(3 * pixels);
    m.exec.copyToHost(rgba.data(), m.rgba.data(), rgba.size());
    for (std::size_t i = 0; i < pixels; ++i) {
        std::memcpy(&out[3 * i], &rgba[4 * i], 3);
    }
    return out;
}

bool interactiveWaterAvailable(std::string* why) {
    if (cudaDeviceAvailable()) {
        return true;
    }
    if (why != nullptr) {
        *why = "no CUDA device is visible";
    }
    return false;
}

}  // namespace weir
