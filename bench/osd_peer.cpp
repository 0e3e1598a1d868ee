// The OpenSubdiv side of fairsub's peer comparison (bench/run_peer.sh).
//
// Uses only OpenSubdiv's public API (Debian's libosd-dev, OpenSubdiv 3.5):
//
//   osd_peer refine  catmark|loop IN.obj LEVELS OUT.ply
//       Reads an OBJ, refines it uniformly with Far::TopologyRefiner and interpolates the
//       points level by level with Far::PrimvarRefiner (double coordinates), and writes the
//       last level as binary little-endian PLY with the layout fairsub writes (double x y z,
//       `list uchar int vertex_indices`). Like fairsub, the output goes to a temporary file
//       beside the target that is flushed, fsync'ed and renamed into place, so both programs
//       do the same I/O work.
//
//   osd_peer stencils catmark|loop IN.obj LEVELS REPS
//       Builds the Far::StencilTable from the control points to the points of level LEVELS
//       (factorized, last level only) and times its application with Osd::CpuEvaluator
//       (single thread, float data as the evaluator requires), minimum over REPS runs.
//
// Boundaries: VTX_BOUNDARY_EDGE_AND_CORNER, fairsub's rule (corners stay put). The comparison
// uses closed meshes, where the option plays no part.
//
// Build: g++ -O3 -std=c++17 -o osd_peer osd_peer.cpp -losdCPU

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/osd/bufferDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

using namespace OpenSubdiv;

namespace {

double now() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

[[noreturn]] void fail(const std::string& msg) {
    std::fprintf(stderr, "osd_peer: %s\n", msg.c_str());
    std::exit(1);
}

// A point with the interface PrimvarRefiner expects.
struct Vertex {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(Vertex const& src, float w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
        p[2] += w * src.p[2];
    }
};

struct Obj {
    std::vector<Vertex> points;
    std::vector<int> face_sizes;
    std::vector<int> corners;
};

// Reads `v` and `f` lines (f tokens may be v, v/vt, v//vn, v/vt/vn; negative indices count
// back); every other statement is skipped.
Obj read_obj(const char* path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(std::string("cannot open ") + path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Obj obj;
    const char* s = text.data();
    const char* end = s + text.size();
    auto skip_space = [&](const char*& c, const char* e) {
        while (c < e && (*c == ' ' || *c == '\t' || *c == '\r')) ++c;
    };
    while (s < end) {
        const char* eol = static_cast<const char*>(std::memchr(s, '\n', end - s));
        if (!eol) eol = end;
        const char* c = s;
        skip_space(c, eol);
        if (c + 1 < eol && c[0] == 'v' && (c[1] == ' ' || c[1] == '\t')) {
            c += 2;
            Vertex v;
            for (double& x : v.p) {
                skip_space(c, eol);
                auto r = std::from_chars(c, eol, x);
                if (r.ec != std::errc()) fail("bad vertex line");
                c = r.ptr;
            }
            obj.points.push_back(v);
        } else if (c + 1 < eol && c[0] == 'f' && (c[1] == ' ' || c[1] == '\t')) {
            c += 2;
            int n = 0;
            while (true) {
                skip_space(c, eol);
                if (c >= eol) break;
                long idx = 0;
                auto r = std::from_chars(c, eol, idx);
                if (r.ec != std::errc()) fail("bad face line");
                c = r.ptr;
                while (c < eol && *c != ' ' && *c != '\t' && *c != '\r') ++c;  // skip /vt/vn
                long v = idx > 0 ? idx - 1 : static_cast<long>(obj.points.size()) + idx;
                obj.corners.push_back(static_cast<int>(v));
                ++n;
            }
            obj.face_sizes.push_back(n);
        }
        s = eol + 1;
    }
    return obj;
}

std::unique_ptr<Far::TopologyRefiner> make_refiner(const char* scheme, Obj const& obj, int levels) {
    Sdc::SchemeType type;
    if (std::strcmp(scheme, "catmark") == 0) {
        type = Sdc::SCHEME_CATMARK;
    } else if (std::strcmp(scheme, "loop") == 0) {
        type = Sdc::SCHEME_LOOP;
    } else {
        fail(std::string("unknown scheme ") + scheme);
    }
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    Far::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(obj.points.size());
    desc.numFaces = static_cast<int>(obj.face_sizes.size());
    desc.numVertsPerFace = obj.face_sizes.data();
    desc.vertIndicesPerFace = obj.corners.data();
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(desc, Factory::Options(type, options)));
    if (!refiner) fail("OpenSubdiv rejected the mesh");
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
    return refiner;
}

// Writes the last level as binary PLY through a temporary file, fsync and rename.
void write_ply(const char* path, Far::TopologyLevel const& level, Vertex const* points) {
    const int nv = level.GetNumVertices();
    const int nf = level.GetNumFaces();
    std::string tmp = std::string(path) + ".tmp-" + std::to_string(getpid());
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) fail("cannot create " + tmp);
    std::vector<char> buf;
    buf.reserve(1 << 20);
    auto flush = [&]() {
        const char* p = buf.data();
        size_t left = buf.size();
        while (left > 0) {
            ssize_t w = ::write(fd, p, left);
            if (w <= 0) fail("write failed");
            p += w;
            left -= static_cast<size_t>(w);
        }
        buf.clear();
    };
    std::ostringstream header;
    header << "ply\nformat binary_little_endian 1.0\ncomment written by osd_peer\nelement vertex "
           << nv << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
           << nf << "\nproperty list uchar int vertex_indices\nend_header\n";
    std::string h = header.str();
    buf.insert(buf.end(), h.begin(), h.end());
    for (int v = 0; v < nv; ++v) {
        const char* p = reinterpret_cast<const char*>(points[v].p);
        buf.insert(buf.end(), p, p + 24);
        if (buf.size() >= (1 << 20)) flush();
    }
    for (int f = 0; f < nf; ++f) {
        Far::ConstIndexArray fv = level.GetFaceVertices(f);
        buf.push_back(static_cast<char>(fv.size()));
        const char* p = reinterpret_cast<const char*>(&fv[0]);
        buf.insert(buf.end(), p, p + 4 * fv.size());
        if (buf.size() >= (1 << 20)) flush();
    }
    flush();
    if (::fsync(fd) != 0) fail("fsync failed");
    ::close(fd);
    if (std::rename(tmp.c_str(), path) != 0) fail("rename failed");
}

int refine(const char* scheme, const char* in, int levels, const char* out) {
    double t0 = now();
    Obj obj = read_obj(in);
    double t1 = now();
    auto refiner = make_refiner(scheme, obj, levels);
    double t2 = now();
    // All levels in one buffer, as in OpenSubdiv's tutorials.
    std::vector<Vertex> verts(refiner->GetNumVerticesTotal());
    std::copy(obj.points.begin(), obj.points.end(), verts.begin());
    Far::PrimvarRefiner primvar(*refiner);
    Vertex* src = verts.data();
    for (int l = 1; l <= levels; ++l) {
        Vertex* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    double t3 = now();
    write_ply(out, refiner->GetLevel(levels), src);
    double t4 = now();
    std::printf(
        "read %.1f ms, topology %.1f ms, primvars %.1f ms, write %.1f ms; %d vertices, %d faces\n",
        (t1 - t0) * 1e3, (t2 - t1) * 1e3, (t3 - t2) * 1e3, (t4 - t3) * 1e3,
        refiner->GetLevel(levels).GetNumVertices(), refiner->GetLevel(levels).GetNumFaces());
    return 0;
}

int stencils(const char* scheme, const char* in, int levels, int reps) {
    Obj obj = read_obj(in);
    auto refiner = make_refiner(scheme, obj, levels);
    double t0 = now();
    Far::StencilTableFactory::Options options;
    options.generateIntermediateLevels = false;
    options.generateOffsets = true;
    std::unique_ptr<Far::StencilTable const> table(
        Far::StencilTableFactory::Create(*refiner, options));
    double build = now() - t0;
    const int rows = table->GetNumStencils();
    std::vector<float> src(3 * obj.points.size());
    for (size_t i = 0; i < obj.points.size(); ++i) {
        for (int k = 0; k < 3; ++k) src[3 * i + k] = static_cast<float>(obj.points[i].p[k]);
    }
    std::vector<float> dst(3 * static_cast<size_t>(rows));
    Osd::BufferDescriptor desc(0, 3, 3);
    double best = 1e30;
    for (int r = 0; r < reps; ++r) {
        double t = now();
        Osd::CpuEvaluator::EvalStencils(src.data(), desc, dst.data(), desc,
                                        table->GetSizes().data(), table->GetOffsets().data(),
                                        table->GetControlIndices().data(),
                                        table->GetWeights().data(), 0, rows);
        best = std::min(best, now() - t);
    }
    const size_t entries = table->GetControlIndices().size();
    std::printf(
        "stencils %d rows, %zu entries (%.1f per row), built in %.0f ms\n"
        "apply 1 thread: %.2f ms (%.1f M points/s)\n",
        rows, entries, static_cast<double>(entries) / rows, build * 1e3, best * 1e3,
        rows / best / 1e6);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 6 && std::strcmp(argv[1], "refine") == 0) {
        return refine(argv[2], argv[3], std::atoi(argv[4]), argv[5]);
    }
    if (argc == 6 && std::strcmp(argv[1], "stencils") == 0) {
        return stencils(argv[2], argv[3], std::atoi(argv[4]), std::atoi(argv[5]));
    }
    std::fprintf(stderr,
                 "usage: osd_peer refine catmark|loop IN.obj LEVELS OUT.ply\n"
                 "       osd_peer stencils catmark|loop IN.obj LEVELS REPS\n");
    return 2;
}
