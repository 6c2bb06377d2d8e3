// OpenGL drawing: shaders, buffers, the offscreen framebuffer and the overlay.
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "render/bitmap_font.h"
#include "render/gl.h"
#include "scene/shape_tessellation.h"

namespace weir {

void checkGl(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(error));
        throw RenderError(std::string("OpenGL error ") + code + " in " + what);
    }
}

namespace {

GLuint compileShader(GLenum type, const std::string& source, const char* name) {
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw RenderError(std::string("shader '") + name + "' does not compile: " + log);
    }
    return shader;
}

}  // namespace

GLuint buildProgram(const std::string& vertex, const std::string& fragment, const char* name) {
    const GLuint vs = compileShader(GL_VERTEX_SHADER, vertex, name);
    const GLuint fs = compileShader(GL_FRAGMENT_SHADER, fragment, name);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw RenderError(std::string("shader '") + name + "' does not link: " + log);
    }
    return program;
}

namespace {

// The particle and solid shading, shared by their fragment shaders; V is taken as straight ahead
// so that a sphere's centre has the same shade anywhere on screen.
constexpr const char* kLightingGlsl = R"(
uniform vec3 lightDir;
uniform vec4 material;  // ambient, diffuse, specular, shininess
vec3 shade(vec3 base, vec3 n) {
    vec3 h = normalize(lightDir + vec3(0.0, 0.0, 1.0));
    float diffuse = max(dot(n, lightDir), 0.0);
    float specular = pow(max(dot(n, h), 0.0), material.w);
    return base * (material.x + material.y * diffuse) + vec3(material.z * specular);
}
)";

constexpr const char* kParticleVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in float value;
uniform mat4 view;
uniform mat4 projection;
uniform float radius;
uniform float pixelScale;  // pixels per unit of view-space size at distance 1
uniform float maxPointSize;
uniform vec2 range;
out vec3 centreView;
out float mapT;
void main() {
    vec4 v = view * vec4(position, 1.0);
    centreView = v.xyz;
    mapT = clamp((value - range.x) / (range.y - range.x), 0.0, 1.0);
    gl_Position = projection * v;
    gl_PointSize = clamp(2.0 * radius * pixelScale / max(-v.z, 1e-6), 1.0, maxPointSize);
}
)";

constexpr const char* kParticleFragment = R"(
in vec3 centreView;
in float mapT;
uniform mat4 projection;
uniform float radius;
uniform sampler1D colourMap;
uniform float useFixedColour;  // 1: fixedColour, not the map (whitewater's white sprites)
uniform vec3 fixedColour;
out vec4 colour;
void main() {
    vec2 p = gl_PointCoord * 2.0 - 1.0;
    p.y = -p.y;  // gl_PointCoord grows downwards
    float r2 = dot(p, p);
    if (r2 > 1.0) {
        discard;
    }
    vec3 n = vec3(p, sqrt(1.0 - r2));
    vec4 clip = projection * vec4(centreView + n * radius, 1.0);
    gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
    vec3 base = useFixedColour > 0.5 ? fixedColour
                                     : texture(colourMap, (0.5 + mapT * 255.0) / 256.0).rgb;
    colour = vec4(shade(base, n), 1.0);
}
)";

// Shared by the water mesh and the grey solids: position and normal in, view-space out.
constexpr const char* kSurfaceVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view;
uniform mat4 projection;
out vec3 positionView;
out vec3 normalView;
void main() {
    vec4 v = view * vec4(position, 1.0);
    positionView = v.xyz;
    normalView = mat3(view) * normal;  // the view matrix is a rotation and a shift
    gl_Position = projection * v;
}
)";

constexpr const char* kSolidFragment = R"(
in vec3 positionView;
in vec3 normalView;
uniform vec3 baseColour;
out vec4 colour;
void main() {
    vec3 n = normalize(normalView);
    if (!gl_FrontFacing) {
        n = -n;
    }
    colour = vec4(shade(baseColour, n), 1.0);
}
)";

// Water: a deep blue body that turns to sky colour at grazing angles (Schlick's Fresnel term with
// water's 2% reflectance head-on), plus a sharp highlight.
constexpr const char* kWaterFragment = R"(
in vec3 positionView;
in vec3 normalView;
out vec4 colour;
void main() {
    vec3 n = normalize(normalView);
    if (!gl_FrontFacing) {
        n = -n;
    }
    vec3 v = normalize(-positionView);
    float cosine = max(dot(n, v), 0.0);
    float fresnel = 0.02 + 0.98 * pow(1.0 - cosine, 5.0);
    vec3 deep = vec3(0.03, 0.20, 0.42);
    vec3 sky = vec3(0.70, 0.84, 0.96);
    vec3 body = deep * (0.45 + 0.55 * max(dot(n, lightDir), 0.0));
    vec3 h = normalize(lightDir + v);
    float highlight = pow(max(dot(n, h), 0.0), 96.0);
    colour = vec4(mix(body, sky, fresnel) + vec3(0.8 * highlight), 1.0);
}
)";

constexpr const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 viewProjection;
void main() {
    gl_Position = viewProjection * vec4(position, 1.0);
}
)";

constexpr const char* kFlatFragment = R"(#version 330 core
uniform vec3 baseColour;
out vec4 colour;
void main() {
    colour = vec4(baseColour, 1.0);
}
)";

// Overlay vertices: pixel position, then either an RGB colour (mapT < 0) or a colour map value.
constexpr const char* kOverlayVertex = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec4 colourOrT;
uniform mat4 pixels;
out vec4 vertexColour;
void main() {
    vertexColour = colourOrT;
    gl_Position = pixels * vec4(position, 0.0, 1.0);
}
)";

constexpr const char* kOverlayFragment = R"(#version 330 core
in vec4 vertexColour;
uniform sampler1D colourMap;
out vec4 colour;
void main() {
    if (vertexColour.a < 0.0) {
        colour = vec4(texture(colourMap, (0.5 + vertexColour.r * 255.0) / 256.0).rgb, 1.0);
    } else {
        colour = vec4(vertexColour.rgb, 1.0);
    }
}
)";

const Rgb kLineColour{0.72f, 0.74f, 0.78f};
const Rgb kObstacleColour{0.58f, 0.56f, 0.52f};
const Rgb kBodyColour{0.72f, 0.48f, 0.26f};  // rigid bodies: wood
const Rgb kTextColour{0.93f, 0.93f, 0.93f};
// Spray, foam and bubbles (whitewater/).
const Rgb kWhitewaterColour{0.92f, 0.94f, 0.96f};

std::string withLighting(const char* body) {
    return std::string("#version 330 core\n") + kLightingGlsl + body;
}

// A vertex array with one interleaved float buffer; `layout` gives each attribute's size.
struct Mesh {
    GLuint vao = 0, vbo = 0, ebo = 0;
    GLsizei count = 0;  // vertices, or indices when ebo is used

    void create(std::initializer_list<int> layout) {
        glGenVertexArrays(1, &vao);
        glGenBuffers(1, &vbo);
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        int stride = 0;
        for (int size : layout) {
            stride += size;
        }
        int offset = 0;
        GLuint index = 0;
        for (int size : layout) {
            glEnableVertexAttribArray(index);
            glVertexAttribPointer(index++, size, GL_FLOAT, GL_FALSE, GLsizei(stride * 4),
                                  reinterpret_cast<void*>(std::uintptr_t(offset * 4)));
            offset += size;
        }
        glBindVertexArray(0);
    }
    void upload(const std::vector<float>& data, GLsizei vertices) {
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(),
                     GL_DYNAMIC_DRAW);
        count = vertices;
    }
    void destroy() {
        glDeleteBuffers(1, &vbo);
        if (ebo != 0) {
            glDeleteBuffers(1, &ebo);
        }
        glDeleteVertexArrays(1, &vao);
    }
};

void setMatrix(GLuint program, const char* name, const Mat4& m) {
    glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, m.m.data());
}
void setVec3(GLuint program, const char* name, const Rgb& c) {
    glUniform3f(glGetUniformLocation(program, name), c.r, c.g, c.b);
}

void setLighting(GLuint program, const ParticleLighting& l) {
    glUniform3f(glGetUniformLocation(program, "lightDir"), l.lightX, l.lightY, l.lightZ);
    glUniform4f(glGetUniformLocation(program, "material"), l.ambient, l.diffuse, l.specular,
                l.shininess);
}

void pushVertex(std::vector<float>& out, const Vec3d& p, const Vec3d& n) {
    out.insert(out.end(), {float(p.x), float(p.y), float(p.z), float(n.x), float(n.y), float(n.z)});
}

// Two triangles per face, outward normals.
void appendBox(const Box& box, std::vector<float>& out) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            Vec3d n{};
            n[axis] = side ? 1 : -1;
            Vec3d corner[4];
            boxFaceCorners(box, axis, side, corner);
            for (int k : {0, 1, 2, 0, 2, 3}) {
                pushVertex(out, corner[k], n);
            }
        }
    }
}

void appendSphere(const SphereShape& sphere, std::vector<float>& out) {
    constexpr int kSlices = 32, kStacks = 16;
    auto point = [&](int i, int j) { return sphereLatticeNormal(i, j, kSlices, kStacks); };
    for (int j = 0; j < kStacks; ++j) {
        for (int i = 0; i < kSlices; ++i) {
            const Vec3d n[4] = {point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)};
            for (int k : {0, 1, 2, 0, 2, 3}) {
                pushVertex(out, sphere.center + n[k] * sphere.radius, n[k]);
            }
        }
    }
}

// A rigid body's shape at its pose: its box, sphere or mesh built about the origin (its centre of
// mass), each vertex then
// rotated by the pose's quaternion and moved to its position.
void appendBody(const BodySpec& body, const BodyPose& pose, std::vector<float>& out) {
    const std::size_t first = out.size();
    if (body.isMesh) {  // flat shaded, about the centre of mass as the pose is
        const Vec3d centre = body.centre();
        for (const auto& t : body.mesh.triangles) {
            const Vec3d a = body.mesh.vertices[std::size_t(t[0])] - centre,
                        b = body.mesh.vertices[std::size_t(t[1])] - centre,
                        c = body.mesh.vertices[std::size_t(t[2])] - centre;
            const Vec3d n = cross(b - a, c - a);
            const double area = length(n);
            if (!(area > 0)) {
                continue;
            }
            for (const Vec3d& p : {a, b, c}) {
                pushVertex(out, p, n / area);
            }
        }
    } else if (body.isSphere) {
        appendSphere({Vec3d(), body.sphere.radius}, out);
    } else {
        const Vec3d half = (body.box.max - body.box.min) * 0.5;
        appendBox({half * -1.0, half}, out);
    }
    const double* q = pose.orientation;
    const Vec3d u(q[0], q[1], q[2]);
    auto turn = [&](const Vec3d& v) {
        const Vec3d t = cross(u, v) * 2.0;
        return v + t * q[3] + cross(u, t);
    };
    for (std::size_t k = first; k + 6 <= out.size(); k += 6) {
        const Vec3d p = turn(Vec3d(out[k], out[k + 1], out[k + 2])) + pose.position;
        const Vec3d n = turn(Vec3d(out[k + 3], out[k + 4], out[k + 5]));
        const float values[6] = {float(p.x), float(p.y), float(p.z),
                                 float(n.x), float(n.y), float(n.z)};
        std::copy(values, values + 6, out.begin() + std::ptrdiff_t(k));
    }
}

void appendBoxEdges(const Box& box, std::vector<float>& out) {
    auto corner = [&](int bits) {
        return Vec3d{(bits & 1) ? box.max.x : box.min.x, (bits & 2) ? box.max.y : box.min.y,
                     (bits & 4) ? box.max.z : box.min.z};
    };
    for (int bits = 0; bits < 8; ++bits) {
        for (int axisBit : {1, 2, 4}) {
            if ((bits & axisBit) == 0) {
                for (const Vec3d& p : {corner(bits), corner(bits | axisBit)}) {
                    out.insert(out.end(), {float(p.x), float(p.y), float(p.z)});
                }
            }
        }
    }
}

// A label for a legend end: short, and plain digits where they fit.
std::string formatValue(double value) {
    char text[32];
    const double magnitude = std::abs(value);
    if (magnitude >= 1000 && magnitude < 1e6) {
        std::snprintf(text, sizeof text, "%.0f", value);
    } else {
        std::snprintf(text, sizeof text, "%.3g", value);
    }
    return text;
}

int overlayScale(int height) { return std::max(1, height / 360); }

}  // namespace

SceneGeometry SceneGeometry::of(const Scene& scene) {
    return {scene.container, scene.obstacleBoxes, scene.obstacleSpheres, scene.bodies};
}

Rgb particleCentreColour(Rgb base, const ParticleLighting& l) {
    const double hx = l.lightX, hy = l.lightY, hz = l.lightZ + 1.0;
    const double hz1 = hz / std::sqrt(hx * hx + hy * hy + hz * hz);  // n = (0, 0, 1)
    const float light = l.ambient + l.diffuse * std::max(l.lightZ, 0.0f);
    const float spec = l.specular * float(std::pow(hz1, double(l.shininess)));
    return {base.r * light + spec, base.g * light + spec, base.b * light + spec};
}

PixelRect legendBarRect(int width, int height) {
    const int s = overlayScale(height);
    PixelRect r;
    r.right = width - 14 * s;
    r.left = r.right - 8 * s;
    r.top = height / 4;
    r.bottom = height - height / 4;
    return r;
}

struct Renderer::Gpu {
    GLuint particleProgram = 0, solidProgram = 0, waterProgram = 0, lineProgram = 0,
           overlayProgram = 0;
    GLuint particleVao = 0, particleBuffers[2] = {0, 0};
    GLuint whitewaterVao = 0, whitewaterBuffers[2] = {0, 0};  // same layout as the particles'
    Mesh solids, bodies, lines, water, overlay;
    GLuint colourMap = 0;
    float maxPointSize = 64;
    // Offscreen targets: multisampled colour + depth, resolved into a single-sampled colour.
    GLuint drawFbo = 0, drawColour = 0, drawDepth = 0, readFbo = 0, readColour = 0;
    int fboWidth = 0, fboHeight = 0, fboSamples = 0;

    void releaseFramebuffers() {
        glDeleteFramebuffers(1, &drawFbo);
        glDeleteFramebuffers(1, &readFbo);
        glDeleteRenderbuffers(1, &drawColour);
        glDeleteRenderbuffers(1, &drawDepth);
        glDeleteRenderbuffers(1, &readColour);
        drawFbo = readFbo = drawColour = drawDepth = readColour = 0;
        fboWidth = fboHeight = fboSamples = 0;
    }

    void ensureFramebuffers(int width, int height, int samples) {
        if (width == fboWidth && height == fboHeight && samples == fboSamples) {
            return;
        }
        releaseFramebuffers();
        auto storage = [&](GLuint& rb, GLenum format, int s) {
            glGenRenderbuffers(1, &rb);
            glBindRenderbuffer(GL_RENDERBUFFER, rb);
            if (s > 1) {
                glRenderbufferStorageMultisample(GL_RENDERBUFFER, s, format, width, height);
            } else {
                glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
            }
        };
        storage(drawColour, GL_RGBA8, samples);
        storage(drawDepth, GL_DEPTH_COMPONENT24, samples);
        glGenFramebuffers(1, &drawFbo);
        glBindFramebuffer(GL_FRAMEBUFFER, drawFbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  drawColour);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, drawDepth);
        const bool drawOk = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
        storage(readColour, GL_RGBA8, 1);
        glGenFramebuffers(1, &readFbo);
        glBindFramebuffer(GL_FRAMEBUFFER, readFbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  readColour);
        const bool readOk = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
        if (!drawOk || !readOk) {
            releaseFramebuffers();
            throw RenderError("cannot make a " + std::to_string(width) + "x" +
                              std::to_string(height) + " offscreen framebuffer with " +
                              std::to_string(samples) + " samples");
        }
        fboWidth = width;
        fboHeight = height;
        fboSamples = samples;
        checkGl("offscreen framebuffer");
    }
};

Renderer::Renderer() : gpu_(std::make_unique<Gpu>()) {
    Gpu& g = *gpu_;
    g.particleProgram =
        buildProgram(kParticleVertex, withLighting(kParticleFragment), "particle sprites");
    g.solidProgram = buildProgram(kSurfaceVertex, withLighting(kSolidFragment), "obstacles");
    g.waterProgram = buildProgram(kSurfaceVertex, withLighting(kWaterFragment), "water surface");
    g.lineProgram = buildProgram(kLineVertex, kFlatFragment, "lines");
    g.overlayProgram = buildProgram(kOverlayVertex, kOverlayFragment, "overlay");

    // Points: positions (3 floats) in buffer 0, a value each (1 float) in buffer 1.
    auto makePointArrays = [](GLuint& vao, GLuint buffers[2]) {
        glGenVertexArrays(1, &vao);
        glGenBuffers(2, buffers);
        glBindVertexArray(vao);
        for (GLuint attribute : {0U, 1U}) {
            glBindBuffer(GL_ARRAY_BUFFER, buffers[attribute]);
            glEnableVertexAttribArray(attribute);
            glVertexAttribPointer(attribute, attribute == 0 ? 3 : 1, GL_FLOAT, GL_FALSE, 0,
                                  nullptr);
        }
    };
    makePointArrays(g.particleVao, g.particleBuffers);
    makePointArrays(g.whitewaterVao, g.whitewaterBuffers);
    glBindVertexArray(0);
    g.solids.create({3, 3});
    g.bodies.create({3, 3});
    g.water.create({3, 3});
    g.lines.create({3});
    g.overlay.create({2, 4});

    // The colour map as a 256-texel 1D texture, sampled at texel centres.
    std::vector<float> texels;
    for (int i = 0; i < 256; ++i) {
        const Rgb c = viridis(i / 255.0);
        texels.insert(texels.end(), {c.r, c.g, c.b});
    }
    glGenTextures(1, &g.colourMap);
    glBindTexture(GL_TEXTURE_1D, g.colourMap);
    glTexImage1D(GL_TEXTURE_1D, 0, GL_RGB8, 256, 0, GL_RGB, GL_FLOAT, texels.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);

    GLfloat sizes[2] = {1, 64};
    glGetFloatv(GL_POINT_SIZE_RANGE, sizes);
    g.maxPointSize = sizes[1];
    checkGl("renderer set-up");
}

Renderer::~Renderer() {
    Gpu& g = *gpu_;
    for (GLuint program :
         {g.particleProgram, g.solidProgram, g.waterProgram, g.lineProgram, g.overlayProgram}) {
        glDeleteProgram(program);
    }
    glDeleteBuffers(2, g.particleBuffers);
    glDeleteVertexArrays(1, &g.particleVao);
    glDeleteBuffers(2, g.whitewaterBuffers);
    glDeleteVertexArrays(1, &g.whitewaterVao);
    for (Mesh* mesh : {&g.solids, &g.bodies, &g.lines, &g.water, &g.overlay}) {
        mesh->destroy();
    }
    glDeleteTextures(1, &g.colourMap);
    g.releaseFramebuffers();
}

void Renderer::setGeometry(const SceneGeometry& geometry) {
    std::vector<float> solids;
    for (const Box& box : geometry.obstacleBoxes) {
        appendBox(box, solids);
    }
    for (const SphereShape& sphere : geometry.obstacleSpheres) {
        appendSphere(sphere, solids);
    }
    gpu_->solids.upload(solids, GLsizei(solids.size() / 6));
    std::vector<float> lines;
    appendBoxEdges(geometry.container, lines);
    gpu_->lines.upload(lines, GLsizei(lines.size() / 3));
    checkGl("scene geometry upload");
}

void Renderer::setBodies(const std::vector<BodySpec>& bodies, const std::vector<BodyPose>& poses) {
    std::vector<float> solids;
    for (std::size_t i = 0; i < std::min(bodies.size(), poses.size()); ++i) {
        appendBody(bodies[i], poses[i], solids);
    }
    gpu_->bodies.upload(solids, GLsizei(solids.size() / 6));
    checkGl("rigid body upload");
}

void Renderer::setParticles(const HostParticles& particles, ColourField field, double radius) {
    const std::size_t n = particles.size();
    std::vector<float> positions(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        positions[3 * i] = float(particles.x[i]);
        positions[3 * i + 1] = float(particles.y[i]);
        positions[3 * i + 2] = float(particles.z[i]);
    }
    const std::vector<float> values = fieldValues(particles, field);
    if (field != field_) {
        autoRange_ = true;  // a range set for another field means nothing for this one
    }
    if (autoRange_) {
        range_ = robustRange(values, field);
    }
    field_ = field;
    radius_ = radius;
    particleCount_ = n;
    reserved_ = n;
    glBindBuffer(GL_ARRAY_BUFFER, gpu_->particleBuffers[0]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(float)), positions.data(),
                 GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, gpu_->particleBuffers[1]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(values.size() * sizeof(float)), values.data(),
                 GL_STREAM_DRAW);
    checkGl("particle upload");
}

void Renderer::setWhitewater(const DiffuseParticles& whitewater, double radius) {
    // Grouped by kind, so that each kind is one draw at its own size.
    std::vector<float> positions;
    positions.reserve(3 * whitewater.size());
    for (int kind = 0; kind < kDiffuseKinds; ++kind) {
        whitewaterCounts_[kind] = 0;
        for (std::size_t k = 0; k < whitewater.size(); ++k) {
            if (whitewater.kind[k] == kind) {
                positions.insert(positions.end(),
                                 {whitewater.x[k], whitewater.y[k], whitewater.z[k]});
                ++whitewaterCounts_[kind];
            }
        }
    }
    const std::vector<float> values(whitewater.size(), 0.0f);
    whitewaterRadius_ = radius;
    glBindBuffer(GL_ARRAY_BUFFER, gpu_->whitewaterBuffers[0]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(float)), positions.data(),
                 GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, gpu_->whitewaterBuffers[1]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(values.size() * sizeof(float)), values.data(),
                 GL_STREAM_DRAW);
    checkGl("whitewater upload");
}

std::pair<unsigned, unsigned> Renderer::reserveParticleBuffers(std::size_t n) {
    if (n != reserved_) {
        glBindBuffer(GL_ARRAY_BUFFER, gpu_->particleBuffers[0]);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * 3 * sizeof(float)), nullptr, GL_STREAM_DRAW);
        glBindBuffer(GL_ARRAY_BUFFER, gpu_->particleBuffers[1]);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(float)), nullptr, GL_STREAM_DRAW);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        checkGl("particle buffer storage");
        reserved_ = n;
    }
    return {gpu_->particleBuffers[0], gpu_->particleBuffers[1]};
}

void Renderer::setFilledParticles(std::size_t n, ColourField field, double radius) {
    if (n > reserved_) {
        throw std::invalid_argument("setFilledParticles: " + std::to_string(n) +
                                    " particles, but the buffers hold " +
                                    std::to_string(reserved_));
    }
    if (field != field_) {
        autoRange_ = true;
    }
    field_ = field;
    radius_ = radius;
    particleCount_ = n;
}

void Renderer::setColourRange(const ValueRange& range) {
    autoRange_ = false;
    range_ = range;
    if (!(range_.hi > range_.lo)) {
        range_.hi = range_.lo + 1e-6;
    }
}

void Renderer::setMesh(const TriangleMesh& mesh) {
    if (mesh.normals.size() != mesh.positions.size()) {
        throw std::invalid_argument("triangle mesh has " + std::to_string(mesh.positions.size()) +
                                    " positions but " + std::to_string(mesh.normals.size()) +
                                    " normals");
    }
    for (std::uint32_t index : mesh.indices) {
        if (index >= mesh.positions.size()) {
            throw std::invalid_argument("triangle mesh index " + std::to_string(index) +
                                        " is past its " + std::to_string(mesh.positions.size()) +
                                        " vertices");
        }
    }
    std::vector<float> vertices;
    vertices.reserve(mesh.positions.size() * 6);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3f& p = mesh.positions[i];
        const Vec3f& n = mesh.normals[i];
        vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    Mesh& water = gpu_->water;
    water.upload(vertices, GLsizei(mesh.positions.size()));
    glBindVertexArray(water.vao);
    if (water.ebo == 0) {
        glGenBuffers(1, &water.ebo);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, water.ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_DYNAMIC_DRAW);
    glBindVertexArray(0);
    water.count = GLsizei(mesh.indices.size() / 3 * 3);
    checkGl("mesh upload");
}

void Renderer::draw(const OrbitCamera& camera, int width, int height) {
    Gpu& g = *gpu_;
    const Mat4 view = camera.view();
    const Mat4 projection = camera.projection(double(width) / height);
    const ParticleLighting lighting;

    glViewport(0, 0, width, height);
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1);
    glClearDepth(1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    if (g.lines.count > 0) {
        glUseProgram(g.lineProgram);
        setMatrix(g.lineProgram, "viewProjection", projection * view);
        setVec3(g.lineProgram, "baseColour", kLineColour);
        glBindVertexArray(g.lines.vao);
        glDrawArrays(GL_LINES, 0, g.lines.count);
    }
    // The obstacles (grey) and the rigid bodies (wood): lit solids of one colour each.
    for (const auto& [mesh, colour] :
         {std::pair<const Mesh*, Rgb>{&g.solids, kObstacleColour}, {&g.bodies, kBodyColour}}) {
        if (mesh->count > 0) {
            glUseProgram(g.solidProgram);
            setMatrix(g.solidProgram, "view", view);
            setMatrix(g.solidProgram, "projection", projection);
            setVec3(g.solidProgram, "baseColour", colour);
            setLighting(g.solidProgram, lighting);
            glBindVertexArray(mesh->vao);
            glDrawArrays(GL_TRIANGLES, 0, mesh->count);
        }
    }
    if (mode_ == RenderMode::Surface && g.water.count > 0) {
        glUseProgram(g.waterProgram);
        setMatrix(g.waterProgram, "view", view);
        setMatrix(g.waterProgram, "projection", projection);
        setLighting(g.waterProgram, lighting);
        glBindVertexArray(g.water.vao);
        glDrawElements(GL_TRIANGLES, g.water.count, GL_UNSIGNED_INT, nullptr);
    }
    if (mode_ == RenderMode::Particles && particleCount_ > 0) {
        glEnable(GL_PROGRAM_POINT_SIZE);
        glUseProgram(g.particleProgram);
        setMatrix(g.particleProgram, "view", view);
        setMatrix(g.particleProgram, "projection", projection);
        glUniform1f(glGetUniformLocation(g.particleProgram, "radius"), float(radius_));
        glUniform1f(glGetUniformLocation(g.particleProgram, "pixelScale"),
                    0.5f * float(height) * projection.at(1, 1));
        glUniform1f(glGetUniformLocation(g.particleProgram, "maxPointSize"), g.maxPointSize);
        glUniform2f(glGetUniformLocation(g.particleProgram, "range"), float(range_.lo),
                    float(range_.hi));
        setLighting(g.particleProgram, lighting);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_1D, g.colourMap);
        glUniform1i(glGetUniformLocation(g.particleProgram, "colourMap"), 0);
        glBindVertexArray(g.particleVao);
        glDrawArrays(GL_POINTS, 0, GLsizei(particleCount_));
    }
    // Spray, foam and bubbles: white sprites over the particles or the surface, foam largest
    // (the sizes of the water look's octahedra).
    if (whitewaterCounts_[0] + whitewaterCounts_[1] + whitewaterCounts_[2] > 0) {
        glEnable(GL_PROGRAM_POINT_SIZE);
        glUseProgram(g.particleProgram);
        setMatrix(g.particleProgram, "view", view);
        setMatrix(g.particleProgram, "projection", projection);
        glUniform1f(glGetUniformLocation(g.particleProgram, "pixelScale"),
                    0.5f * float(height) * projection.at(1, 1));
        glUniform1f(glGetUniformLocation(g.particleProgram, "maxPointSize"), g.maxPointSize);
        glUniform1f(glGetUniformLocation(g.particleProgram, "useFixedColour"), 1.0f);
        setVec3(g.particleProgram, "fixedColour", kWhitewaterColour);
        setLighting(g.particleProgram, lighting);
        glBindVertexArray(g.whitewaterVao);
        const float sizes[kDiffuseKinds] = {0.7f, 1.0f, 0.5f};  // spray, foam, bubbles
        GLint first = 0;
        for (int kind = 0; kind < kDiffuseKinds; ++kind) {
            glUniform1f(glGetUniformLocation(g.particleProgram, "radius"),
                        float(whitewaterRadius_) * sizes[kind]);
            glDrawArrays(GL_POINTS, first, GLsizei(whitewaterCounts_[kind]));
            first += GLint(whitewaterCounts_[kind]);
        }
        glUniform1f(glGetUniformLocation(g.particleProgram, "useFixedColour"), 0.0f);
    }
    drawOverlay(width, height);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGl("draw");
}

void Renderer::drawOverlayOnly(int width, int height) {
    glViewport(0, 0, width, height);
    drawOverlay(width, height);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGl("overlay");
}

void Renderer::drawOverlay(int width, int height) {
    Gpu& g = *gpu_;
    const int s = overlayScale(height);
    std::vector<float> vertices;  // x, y, then r, g, b, 1 or t, 0, 0, -1
    auto addSolid = [&](const std::vector<float>& xy, const Rgb& c) {
        for (std::size_t i = 0; i + 1 < xy.size(); i += 2) {
            vertices.insert(vertices.end(), {xy[i], xy[i + 1], c.r, c.g, c.b, 1.0f});
        }
    };
    auto addText = [&](const std::string& text, float x, float top, const Rgb& c) {
        std::vector<float> xy;
        appendTextTriangles(text, x, top, s, xy);
        addSolid(xy, c);
    };
    const float h = float(height);
    if (showLegend_ && mode_ == RenderMode::Particles) {
        const PixelRect r = legendBarRect(width, height);
        const float x0 = float(r.left), x1 = float(r.right);
        const float yLo = h - float(r.bottom), yHi = h - float(r.top);  // GL rows grow upwards
        // A thin frame, then the bar: one quad from t = 0 to t = 1, interpolated by the texture.
        const float f = float(s);
        addSolid({x0 - f, yLo - f, x1 + f, yLo - f, x1 + f, yHi + f, x0 - f, yLo - f, x1 + f,
                  yHi + f, x0 - f, yHi + f},
                 kLineColour);
        const float quad[6][3] = {{x0, yLo, 0}, {x1, yLo, 0}, {x1, yHi, 1},
                                  {x0, yLo, 0}, {x1, yHi, 1}, {x0, yHi, 1}};
        for (const auto& v : quad) {
            vertices.insert(vertices.end(), {v[0], v[1], v[2], 0, 0, -1});
        }
        const std::string hi = formatValue(range_.hi), lo = formatValue(range_.lo);
        const float gap = float(4 * s);
        addText(hi, x0 - gap - float(textWidth(hi, s)), yHi, kTextColour);
        addText(lo, x0 - gap - float(textWidth(lo, s)), yLo + float(kGlyphHeight * s), kTextColour);
        const std::string title =
            std::string(colourFieldName(field_)) + " " + colourFieldUnit(field_);
        addText(title, x1 - float(textWidth(title, s)), yHi + float((kGlyphHeight + 6) * s),
                kTextColour);
    }
    for (std::size_t line = 0; line < overlay_.size(); ++line) {
        addText(overlay_[line], float(8 * s), h - float(8 * s) - float(line * 10 * s), kTextColour);
    }
    if (vertices.empty()) {
        return;
    }
    glDisable(GL_DEPTH_TEST);
    glUseProgram(g.overlayProgram);
    setMatrix(g.overlayProgram, "pixels", pixelOrtho(width, height));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_1D, g.colourMap);
    glUniform1i(glGetUniformLocation(g.overlayProgram, "colourMap"), 0);
    g.overlay.upload(vertices, GLsizei(vertices.size() / 6));
    glBindVertexArray(g.overlay.vao);
    glDrawArrays(GL_TRIANGLES, 0, g.overlay.count);
    glEnable(GL_DEPTH_TEST);
}

void Renderer::drawOffscreenAndWait(const OrbitCamera& camera, int width, int height) {
    Gpu& g = *gpu_;
    g.ensureFramebuffers(width, height, std::max(samples_, 1));
    glBindFramebuffer(GL_FRAMEBUFFER, g.drawFbo);
    draw(camera, width, height);
    glFinish();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("drawing offscreen");
}

Image Renderer::renderImage(const OrbitCamera& camera, int width, int height) {
    if (width < 16 || height < 16 || width > 16384 || height > 16384) {
        throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " must be within 16..16384 pixels");
    }
    Gpu& g = *gpu_;
    g.ensureFramebuffers(width, height, std::max(samples_, 1));
    glBindFramebuffer(GL_FRAMEBUFFER, g.drawFbo);
    draw(camera, width, height);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.drawFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g.readFbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, g.readFbo);
    std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("reading the image back");
    Image image(width, height);
    for (int y = 0; y < height; ++y) {
        const std::uint8_t* src =
            rgba.data() + std::size_t(height - 1 - y) * std::size_t(width) * 4;
        std::uint8_t* dst = image.rgb.data() + std::size_t(y) * std::size_t(width) * 3;
        for (int x = 0; x < width; ++x) {
            dst[3 * x] = src[4 * x];
            dst[3 * x + 1] = src[4 * x + 1];
            dst[3 * x + 2] = src[4 * x + 2];
        }
    }
    return image;
}

double estimateParticleRadius(const HostParticles& particles) {
    const std::size_t n = particles.size();
    if (n < 2) {
        return 0.01;
    }
    const std::size_t samples = std::min<std::size_t>(n, 31);
    std::vector<double> nearest;
    for (std::size_t k = 0; k < samples; ++k) {
        const std::size_t i = k * (n / samples);
        double best = INFINITY;
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) {
                continue;
            }
            const double dx = particles.x[j] - particles.x[i], dy = particles.y[j] - particles.y[i],
                         dz = particles.z[j] - particles.z[i];
            const double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 > 0 && d2 < best) {
                best = d2;
            }
        }
        if (std::isfinite(best)) {
            nearest.push_back(std::sqrt(best));
        }
    }
    if (nearest.empty()) {
        return 0.01;
    }
    std::nth_element(nearest.begin(), nearest.begin() + std::ptrdiff_t(nearest.size() / 2),
                     nearest.end());
    return 0.5 * nearest[nearest.size() / 2];
}

}  // namespace weir
