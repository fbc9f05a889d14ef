#include "synth/ray_index.hpp"

#include "synth/scene.hpp"

#include <embree3/rtcore.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace vobench::synth {

struct RayIndex::Handles {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
};

namespace {

RTCRay make_ray(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max) {
    RTCRay r;
    r.org_x = static_cast<float>(o.x());
    r.org_y = static_cast<float>(o.y());
    r.org_z = static_cast<float>(o.z());
    r.dir_x = static_cast<float>(d.x());
    r.dir_y = static_cast<float>(d.y());
    r.dir_z = static_cast<float>(d.z());
    r.tnear = static_cast<float>(t_min);
    r.tfar = static_cast<float>(std::min(t_max, static_cast<double>(std::numeric_limits<float>::max())));
    r.time = 0;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    return r;
}

}  // namespace

RayIndex::RayIndex(const std::vector<Box>& boxes) : handles_(std::make_unique<Handles>()) {
    handles_->device = rtcNewDevice(nullptr);
    if (!handles_->device)
        throw std::runtime_error("Embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    handles_->scene = rtcNewScene(handles_->device);
    rtcSetSceneBuildQuality(handles_->scene, RTC_BUILD_QUALITY_HIGH);
    if (!boxes.empty()) {
        RTCGeometry g = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 8 * boxes.size()));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 12 * boxes.size()));
        for (std::size_t b = 0; b < boxes.size(); ++b) {
            // Corner c has x from bit 0, y from bit 1, z from bit 2 (0: min, 1: max).
            for (unsigned c = 0; c < 8; ++c)
                for (int a = 0; a < 3; ++a)
                    v[(8 * b + c) * 3 + static_cast<unsigned>(a)] = static_cast<float>((c >> a) & 1u ? boxes[b].max[a] : boxes[b].min[a]);
            // Face f = 2·axis + side: the four corners with that axis bit, around the face, as two triangles.
            for (unsigned f = 0; f < 6; ++f) {
                const unsigned axis = f / 2, side = f % 2, p = (axis + 1) % 3, q = (axis + 2) % 3;
                auto corner = [&](unsigned bp, unsigned bq) {
                    return static_cast<unsigned>(8 * b) + (side << axis) + (bp << p) + (bq << q);
                };
                const unsigned quad[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
                unsigned* t = idx + (12 * b + 2 * f) * 3;
                t[0] = quad[0], t[1] = quad[1], t[2] = quad[2];
                t[3] = quad[0], t[4] = quad[2], t[5] = quad[3];
            }
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(handles_->scene, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(handles_->scene);
    if (const RTCError e = rtcGetDeviceError(handles_->device); e != RTC_ERROR_NONE)
        throw std::runtime_error("Embree: cannot build the scene (error " + std::to_string(e) + ")");
}

RayIndex::~RayIndex() {
    if (handles_->scene) rtcReleaseScene(handles_->scene);
    if (handles_->device) rtcReleaseDevice(handles_->device);
}

bool RayIndex::nearest(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max, IndexHit& hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = make_ray(o, d, t_min, t_max);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(handles_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    const unsigned face = (rh.hit.primID % 12) / 2;
    hit.t = rh.ray.tfar;
    hit.box = static_cast<int>(rh.hit.primID / 12);
    hit.axis = static_cast<int>(face / 2);
    hit.max_side = face % 2 == 1;
    return true;
}

void RayIndex::nearest_packet(const Eigen::Vector3d& o, const Eigen::Vector3d* dirs, int count, double t_min, double t_max,
                              IndexHit* hits) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(32) int valid[kPacket];
    RTCRayHit8 rh;
    const float far = static_cast<float>(std::min(t_max, static_cast<double>(std::numeric_limits<float>::max())));
    for (int i = 0; i < kPacket; ++i) {
        // Lanes past `count` are switched off (valid 0) and carry a copy of the first ray.
        const Eigen::Vector3d& d = dirs[i < count ? i : 0];
        valid[i] = i < count ? -1 : 0;
        rh.ray.org_x[i] = static_cast<float>(o.x());
        rh.ray.org_y[i] = static_cast<float>(o.y());
        rh.ray.org_z[i] = static_cast<float>(o.z());
        rh.ray.dir_x[i] = static_cast<float>(d.x());
        rh.ray.dir_y[i] = static_cast<float>(d.y());
        rh.ray.dir_z[i] = static_cast<float>(d.z());
        rh.ray.tnear[i] = static_cast<float>(t_min);
        rh.ray.tfar[i] = far;
        rh.ray.time[i] = 0;
        rh.ray.mask[i] = 0xffffffffu;
        rh.ray.id[i] = static_cast<unsigned>(i);
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, handles_->scene, &context, &rh);
    for (int i = 0; i < count; ++i) {
        if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
            hits[i] = IndexHit{};
            continue;
        }
        const unsigned face = (rh.hit.primID[i] % 12) / 2;
        hits[i].t = rh.ray.tfar[i];
        hits[i].box = static_cast<int>(rh.hit.primID[i] / 12);
        hits[i].axis = static_cast<int>(face / 2);
        hits[i].max_side = face % 2 == 1;
    }
}

bool RayIndex::any(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(o, d, t_min, t_max);
    rtcOccluded1(handles_->scene, &context, &ray);
    return ray.tfar < 0;  // Embree sets tfar to −∞ on an occlusion
}

}  // namespace vobench::synth
