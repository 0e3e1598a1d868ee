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
//   osd_peer patches IN.obj ISOLATION POINTS REPS OUT.bin
//       The adaptive patch table of Catmull-Clark (Far::TopologyRefiner::RefineAdaptive to
//       ISOLATION levels, Far::PatchTableFactory with Gregory end caps in double precision, the
//       double Far::StencilTable from the control points to the refined and local points, and
//       Far::PatchMap), timed as a whole; then the points of the refined and local vertices
//       from the control points (the re-application) and the evaluation of the POINTS-point
//       grid of fairsub-bench's grid_points (per face a k x k grid) with PatchMap::FindPatch
//       and PatchTable::EvaluateBasis (point, first and second derivatives), minimum over REPS;
//       the points go to OUT.bin (little-endian double x y z per point).
//
// Boundaries: VTX_BOUNDARY_EDGE_AND_CORNER, fairsub's rule (corners stay put). The comparison
// uses closed meshes, where the option plays no part.
//
// Build: g++ -O3 -std=c++17 -o osd_peer osd_peer.cpp -losdCPU

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
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
    // OpenSubdiv tags `t crease 2/1/0 a b s` (one edge per line, as fairsub-bench writes them)
    // and `t corner 1/1/0 v s`.
    std::vector<int> crease_pairs;
    std::vector<float> crease_weights;
    std::vector<int> corner_vertices;
    std::vector<float> corner_weights;
};

// Reads `v` and `f` lines (f tokens may be v, v/vt, v//vn, v/vt/vn; negative indices count
// back) and the one-edge `t crease 2/1/0` and one-vertex `t corner 1/1/0` tags; every other
// statement is skipped.
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
        } else if (c + 1 < eol && c[0] == 't' && (c[1] == ' ' || c[1] == '\t')) {
            std::string line(c + 2, eol);
            char name[32] = {0};
            int a = 0, b = 0;
            float w = 0.0f;
            if (std::sscanf(line.c_str(), " crease 2/1/0 %d %d %f", &a, &b, &w) == 3) {
                obj.crease_pairs.push_back(a);
                obj.crease_pairs.push_back(b);
                obj.crease_weights.push_back(w);
            } else if (std::sscanf(line.c_str(), " corner 1/1/0 %d %f", &a, &w) == 2) {
                obj.corner_vertices.push_back(a);
                obj.corner_weights.push_back(w);
            } else if (std::sscanf(line.c_str(), " %31s", name) == 1) {
                fail(std::string("unsupported tag line: t") + line);
            }
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
    desc.numCreases = static_cast<int>(obj.crease_weights.size());
    desc.creaseVertexIndexPairs = obj.crease_pairs.data();
    desc.creaseWeights = obj.crease_weights.data();
    desc.numCorners = static_cast<int>(obj.corner_weights.size());
    desc.cornerVertexIndices = obj.corner_vertices.data();
    desc.cornerWeights = obj.corner_weights.data();
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

// A double point with the interface StencilTableReal<double>::UpdateValues expects.
struct DVertex {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(DVertex const& src, double w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
        p[2] += w * src.p[2];
    }
};

int patches(const char* in, int isolation, long count, int reps, const char* out) {
    Obj obj = read_obj(in);
    const int nf = static_cast<int>(obj.face_sizes.size());
    for (int n : obj.face_sizes) {
        if (n != 4) fail("the patch peer takes quad meshes (PatchMap face = input face)");
    }
    // the evaluation grid, as fairsub-bench's grid_points
    long k = 1;
    while (static_cast<long>(nf) * k * k < count) ++k;
    std::vector<int> gf;
    std::vector<double> gu, gv;
    for (int f = 0; f < nf && static_cast<long>(gf.size()) < count; ++f) {
        for (long a = 0; a < k && static_cast<long>(gf.size()) < count; ++a) {
            for (long b = 0; b < k && static_cast<long>(gf.size()) < count; ++b) {
                gf.push_back(f);
                gu.push_back((a + 0.5) / k);
                gv.push_back((b + 0.5) / k);
            }
        }
    }
    const size_t n = gf.size();
    std::vector<double> result(3 * n);
    double best_build = 1e30, best_apply = 1e30, best_eval = 1e30, best_eval_p = 1e30;
    size_t npatches = 0, npoints = 0;
    for (int r = 0; r < reps; ++r) {
        double t0 = now();
        Sdc::Options options;
        options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        Far::TopologyDescriptor desc;
        desc.numVertices = static_cast<int>(obj.points.size());
        desc.numFaces = nf;
        desc.numVertsPerFace = obj.face_sizes.data();
        desc.vertIndicesPerFace = obj.corners.data();
        using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
        std::unique_ptr<Far::TopologyRefiner> refiner(
            Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, options)));
        if (!refiner) fail("OpenSubdiv rejected the mesh");
        Far::PatchTableFactory::Options po(isolation);
        po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
        po.SetPatchPrecision<double>();
        refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
        std::unique_ptr<Far::PatchTable> table(Far::PatchTableFactory::Create(*refiner, po));
        Far::StencilTableFactoryReal<double>::Options so;
        so.generateIntermediateLevels = true;
        so.generateOffsets = true;
        std::unique_ptr<Far::StencilTableReal<double> const> st(
            Far::StencilTableFactoryReal<double>::Create(*refiner, so));
        if (auto const* lp = table->GetLocalPointStencilTable<double>()) {
            auto const* all = Far::StencilTableFactoryReal<double>::AppendLocalPointStencilTable(
                *refiner, st.get(), lp);
            if (all) st.reset(all);
        }
        Far::PatchMap map(*table);
        double t1 = now();
        best_build = std::min(best_build, t1 - t0);
        // control points -> every patch point (refined vertices, then local points)
        const int ncoarse = refiner->GetLevel(0).GetNumVertices();
        std::vector<DVertex> verts(ncoarse + st->GetNumStencils());
        for (int i = 0; i < ncoarse; ++i) {
            for (int c = 0; c < 3; ++c) verts[i].p[c] = obj.points[i].p[c];
        }
        double t2 = now();
        st->UpdateValues(verts.data(), verts.data() + ncoarse);
        best_apply = std::min(best_apply, now() - t2);
        // evaluation: point, first and second derivatives
        double t3 = now();
        double wP[20], wDu[20], wDv[20], wDuu[20], wDuv[20], wDvv[20];
        for (size_t i = 0; i < n; ++i) {
            auto const* h = map.FindPatch(gf[i], gu[i], gv[i]);
            if (!h) fail("PatchMap found no patch");
            table->EvaluateBasis(*h, gu[i], gv[i], wP, wDu, wDv, wDuu, wDuv, wDvv);
            Far::ConstIndexArray cvs = table->GetPatchVertices(*h);
            double acc[6][3] = {};
            for (int j = 0; j < cvs.size(); ++j) {
                const double* q = verts[cvs[j]].p;
                for (int c = 0; c < 3; ++c) {
                    acc[0][c] += wP[j] * q[c];
                    acc[1][c] += wDu[j] * q[c];
                    acc[2][c] += wDv[j] * q[c];
                    acc[3][c] += wDuu[j] * q[c];
                    acc[4][c] += wDuv[j] * q[c];
                    acc[5][c] += wDvv[j] * q[c];
                }
            }
            double keep = 0.0;
            for (int d = 1; d < 6; ++d) keep += acc[d][0] + acc[d][1] + acc[d][2];
            result[3 * i] = acc[0][0] + 0.0 * keep;
            result[3 * i + 1] = acc[0][1];
            result[3 * i + 2] = acc[0][2];
        }
        best_eval = std::min(best_eval, now() - t3);
        // evaluation of the point only
        double t4 = now();
        double sink = 0.0;
        for (size_t i = 0; i < n; ++i) {
            auto const* h = map.FindPatch(gf[i], gu[i], gv[i]);
            table->EvaluateBasis(*h, gu[i], gv[i], wP);
            Far::ConstIndexArray cvs = table->GetPatchVertices(*h);
            double acc[3] = {};
            for (int j = 0; j < cvs.size(); ++j) {
                for (int c = 0; c < 3; ++c) acc[c] += wP[j] * verts[cvs[j]].p[c];
            }
            sink += acc[0] + acc[1] + acc[2];
        }
        best_eval_p = std::min(best_eval_p, now() - t4);
        if (sink == 12345.678) std::printf(" ");
        npatches = static_cast<size_t>(table->GetNumPatchesTotal());
        npoints = static_cast<size_t>(st->GetNumStencils());
    }
    std::ofstream f(out, std::ios::binary);
    f.write(reinterpret_cast<const char*>(result.data()), result.size() * sizeof(double));
    if (!f) fail("cannot write the points");
    std::printf(
        "opensubdiv adaptive catmark, %d faces, isolation %d, gregory end caps, double: %zu "
        "patches, %zu refined + local points\n"
        "build (refiner, adaptive refinement, patch table, stencils, patch map): %.1f ms\n"
        "re-apply the stencils to the control points: %.1f ms\n"
        "evaluate %zu points (point, d1, d2): %.1f ms; point only: %.1f ms\n",
        nf, isolation, npatches, npoints, best_build * 1e3, best_apply * 1e3, n,
        best_eval * 1e3, best_eval_p * 1e3);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 7 && std::strcmp(argv[1], "patches") == 0) {
        return patches(argv[2], std::atoi(argv[3]), std::atol(argv[4]), std::atoi(argv[5]),
                       argv[6]);
    }
    if (argc == 6 && std::strcmp(argv[1], "refine") == 0) {
        return refine(argv[2], argv[3], std::atoi(argv[4]), argv[5]);
    }
    if (argc == 6 && std::strcmp(argv[1], "stencils") == 0) {
        return stencils(argv[2], argv[3], std::atoi(argv[4]), std::atoi(argv[5]));
    }
    std::fprintf(stderr,
                 "usage: osd_peer refine catmark|loop IN.obj LEVELS OUT.ply\n"
                 "       osd_peer stencils catmark|loop IN.obj LEVELS REPS\n"
                 "       osd_peer patches IN.obj ISOLATION POINTS REPS OUT.bin\n");
    return 2;
}
