// osd_refine: the OpenSubdiv side of fairsub's peer comparison (tests/osd_peer.rs).
//
// Reads an OpenSubdiv-style OBJ net (with `t` tag lines), refines it uniformly with OpenSubdiv's
// public API (Debian's libosd-dev, OpenSubdiv 3.5: Far::TopologyDescriptor,
// Far::TopologyRefinerFactory, Far::PrimvarRefinerReal<double>) and writes the last level as
// plain text. Build and run through tests/peer/build.sh.
//
// Usage
// -----
//   osd_refine --scheme catmark|loop --levels L
//              [--boundary none|edge-only|edge-and-corner]
//              [--fvar none|corners-only|corners-plus1|corners-plus2|boundaries|all]
//              [--crease-method uniform|chaikin] [--smooth-triangles] [--limit]
//              [--dump FILE] IN.obj OUT.txt
//
// A command-line option overrides the matching tag of the file. Defaults when neither says
// anything: boundary edge-and-corner (fairsub's default; NOTE: OpenSubdiv's own regression
// shapes default to edge-only, and Sdc::Options() to none), fvar `all` (Sdc::Options' default,
// FVAR_LINEAR_ALL), crease method uniform, triangle subdivision catmark.
//
// Input (OBJ subset)
// ------------------
//   v X Y Z [W]        a point (W ignored)
//   vt U V [W]         a texture coordinate (W ignored)
//   f A B C ...        a face; each corner is v, v/vt, v//vn or v/vt/vn; indices count from 1,
//                      negative ones count back from the last v (or vt) read so far. Either
//                      every face has vt indices (one face-varying channel is built) or none.
//   t NAME I/F/S ints floats strings     an OpenSubdiv tag (indices in tags count from 0):
//     crease      ints = vertex pairs (a0 b0 a1 b1 ...), one edge per pair; floats = one
//                 sharpness for all of them or one per pair (OpenSubdiv's regression reader
//                 indexes the floats by the first int's position, floats[2k] for pair k, which
//                 only matters for several pairs with several floats: here it is floats[k]).
//                 Negative sharpness counts as 0; >= 10 is infinitely sharp.
//     corner      ints = vertices; floats = one sharpness for all or one per vertex.
//     hole        ints = faces.
//     interpolateboundary             1 int: 0 none, 1 edge-and-corner, 2 edge-only.
//     facevaryinginterpolateboundary  1 int: 0 none, 1 corners-only, 2 corners-plus1,
//                                     3 corners-plus2, 4 boundaries, 5 all.
//     facevaryingpropagatecorners     accepted and ignored with a warning (OpenSubdiv 3 has no
//                                     such option; corners-plus2 propagates corners).
//     creasemethod    1 string: normal (= uniform) | uniform | chaikin.
//     smoothtriangles 1 string: catmark | smooth (or 1 int: 0 catmark, 1 smooth); Catmark only.
//   Other tags (vertexedit, edgeedit, faceedit, ...) are ignored with a warning on stderr, as
//   OpenSubdiv 3 ignores hierarchical edits. Other statements (vn, o, g, s, usemtl, mtllib, l,
//   comments) are skipped. Bad input stops with a message naming the line.
//
// Output (plain text, one record per line, numbers as %.17g)
// ----------------------------------------------------------
//   osd_refine 1
//   scheme catmark|loop
//   levels L
//   boundary none|edge-only|edge-and-corner
//   fvar none|corners-only|corners-plus1|corners-plus2|boundaries|all
//   crease-method uniform|chaikin
//   triangles catmark|smooth
//   vertices NV            number of vertices of level L
//   faces NF               number of faces of level L (holes included)
//   holes NH               how many of them are holes
//   fvar-values NU         face-varying values of level L (0 without vt)
//   limit 0|1
//   v X Y Z                NV lines: level-L points, in OpenSubdiv's vertex order
//   f H I0 I1 ...          NF lines: H = 1 for a hole face, then the face's vertex indices
//                          (0-based; Catmark faces of level >= 1 are quads, Loop's triangles)
//   vt U V                 NU lines: level-L face-varying values
//   fv J0 J1 ...           NF lines (only when NU > 0): the value index of each face corner
//   lp X Y Z               NV lines (only with --limit): limit position of each vertex
//   lt X1 Y1 Z1 X2 Y2 Z2   NV lines (only with --limit): the two limit tangents
//   lvt U V                NU lines (only with --limit and NU > 0): face-varying limit values
//   end
//
// With --dump FILE, every level 0..L is also written to FILE for hand checks: per vertex its
// point, sharpness and rule (smooth|dart|crease|corner), per edge its two vertices and
// sharpness (after OpenSubdiv's boundary and non-manifold sharpening), per face its vertices
// and hole flag.
//
// Build: g++ -O2 -std=c++17 -o osd_refine osd_refine.cpp -losdCPU

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace OpenSubdiv;

namespace {

[[noreturn]] void fail(const std::string& msg) {
    std::fprintf(stderr, "osd_refine: %s\n", msg.c_str());
    std::exit(2);
}

void warn(const std::string& msg) { std::fprintf(stderr, "osd_refine: warning: %s\n", msg.c_str()); }

// A primvar of D doubles with the interface PrimvarRefiner expects.
template <int D>
struct Val {
    double x[D];
    void Clear(void* = nullptr) {
        for (double& c : x) c = 0.0;
    }
    void AddWithWeight(Val const& s, double w) {
        for (int i = 0; i < D; ++i) x[i] += w * s.x[i];
    }
};
using P3 = Val<3>;
using P2 = Val<2>;

// A tag line: name, ints, floats, strings.
struct Tag {
    std::string name;
    std::vector<long> ints;
    std::vector<double> floats;
    std::vector<std::string> strings;
    int line = 0;
};

struct Net {
    std::vector<P3> points;
    std::vector<P2> uvs;
    std::vector<int> face_sizes;
    std::vector<int> corners;
    std::vector<int> uv_corners;  // one per corner when faces carry vt
    int faces_with_uv = 0;
    std::vector<Tag> tags;
};

std::vector<std::string> split_ws(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string t;
    while (in >> t) out.push_back(t);
    return out;
}

bool parse_double(const std::string& s, double& v) {
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    v = std::strtod(s.c_str(), &end);
    return end && *end == '\0' && errno == 0 && std::isfinite(v);
}

bool parse_long(const std::string& s, long& v) {
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    v = std::strtol(s.c_str(), &end, 10);
    return end && *end == '\0' && errno == 0;
}

// Resolves an OBJ index (1-based, or negative relative to `count` items read so far).
int resolve(long idx, size_t count, const std::string& what, int line) {
    long r = idx > 0 ? idx - 1 : (idx < 0 ? static_cast<long>(count) + idx : -1);
    if (r < 0 || r >= static_cast<long>(count))
        fail("line " + std::to_string(line) + ": " + what + " index " + std::to_string(idx) +
             " out of range (" + std::to_string(count) + " read so far)");
    return static_cast<int>(r);
}

Net read_obj(const char* path) {
    std::ifstream in(path);
    if (!in) fail(std::string("cannot open ") + path);
    Net net;
    std::string raw;
    int lineno = 0;
    while (std::getline(in, raw)) {
        ++lineno;
        // Continuation lines (backslash at the end) join the next line.
        while (!raw.empty() && (raw.back() == '\r')) raw.pop_back();
        while (!raw.empty() && raw.back() == '\\') {
            raw.pop_back();
            std::string next;
            if (!std::getline(in, next)) break;
            ++lineno;
            while (!next.empty() && next.back() == '\r') next.pop_back();
            raw += " " + next;
        }
        size_t hash = raw.find('#');
        if (hash != std::string::npos) raw.resize(hash);
        std::vector<std::string> tok = split_ws(raw);
        if (tok.empty()) continue;
        const std::string& kw = tok[0];
        const std::string where = "line " + std::to_string(lineno) + ": ";
        if (kw == "v") {
            if (tok.size() < 4) fail(where + "a vertex needs 3 coordinates");
            P3 p;
            for (int i = 0; i < 3; ++i)
                if (!parse_double(tok[1 + i], p.x[i])) fail(where + "bad coordinate '" + tok[1 + i] + "'");
            net.points.push_back(p);
        } else if (kw == "vt") {
            if (tok.size() < 3) fail(where + "a texture coordinate needs 2 values");
            P2 t;
            for (int i = 0; i < 2; ++i)
                if (!parse_double(tok[1 + i], t.x[i])) fail(where + "bad texture coordinate '" + tok[1 + i] + "'");
            net.uvs.push_back(t);
        } else if (kw == "f") {
            if (tok.size() < 4) fail(where + "a face needs at least 3 corners");
            int n = static_cast<int>(tok.size()) - 1;
            int with_uv = 0;
            for (int i = 1; i <= n; ++i) {
                const std::string& c = tok[i];
                size_t s1 = c.find('/');
                std::string vs = c.substr(0, s1);
                long vi;
                if (!parse_long(vs, vi)) fail(where + "bad face corner '" + c + "'");
                net.corners.push_back(resolve(vi, net.points.size(), "vertex", lineno));
                if (s1 != std::string::npos) {
                    size_t s2 = c.find('/', s1 + 1);
                    std::string ts = c.substr(s1 + 1, s2 == std::string::npos ? std::string::npos : s2 - s1 - 1);
                    if (!ts.empty()) {
                        long ti;
                        if (!parse_long(ts, ti)) fail(where + "bad texture index in '" + c + "'");
                        net.uv_corners.push_back(resolve(ti, net.uvs.size(), "texture coordinate", lineno));
                        ++with_uv;
                    }
                }
            }
            if (with_uv != 0 && with_uv != n) fail(where + "some corners of the face have a vt index, others not");
            if (with_uv) ++net.faces_with_uv;
            net.face_sizes.push_back(n);
            if (net.faces_with_uv != 0 && net.faces_with_uv != static_cast<int>(net.face_sizes.size()))
                fail(where + "faces with and without vt indices are mixed");
        } else if (kw == "t") {
            if (tok.size() < 3) fail(where + "a tag needs a name and counts I/F/S");
            Tag t;
            t.name = tok[1];
            t.line = lineno;
            long ni = 0, nf = 0, ns = 0;
            if (std::sscanf(tok[2].c_str(), "%ld/%ld/%ld", &ni, &nf, &ns) != 3 || ni < 0 || nf < 0 || ns < 0)
                fail(where + "bad tag counts '" + tok[2] + "' (expected ints/floats/strings)");
            if (static_cast<long>(tok.size()) != 3 + ni + nf + ns)
                fail(where + "tag '" + t.name + "' announces " + std::to_string(ni + nf + ns) + " arguments, has " +
                     std::to_string(tok.size() - 3));
            size_t k = 3;
            for (long i = 0; i < ni; ++i, ++k) {
                long v;
                if (!parse_long(tok[k], v)) fail(where + "bad integer '" + tok[k] + "' in tag " + t.name);
                t.ints.push_back(v);
            }
            for (long i = 0; i < nf; ++i, ++k) {
                double v;
                if (!parse_double(tok[k], v)) fail(where + "bad float '" + tok[k] + "' in tag " + t.name);
                t.floats.push_back(v);
            }
            for (long i = 0; i < ns; ++i, ++k) t.strings.push_back(tok[k]);
            net.tags.push_back(t);
        }
        // Everything else is skipped.
    }
    if (net.face_sizes.empty()) fail(std::string(path) + ": no faces");
    return net;
}

struct Settings {
    Sdc::SchemeType scheme = Sdc::SCHEME_CATMARK;
    int levels = -1;
    int boundary = -1;  // -1: not given on the command line
    int fvar = -1;
    int crease = -1;
    int tri = -1;
    bool limit = false;
    std::string dump;
    std::string in, out;
};

const char* const kBoundary[] = {"none", "edge-only", "edge-and-corner"};
const char* const kFvar[] = {"none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"};
const char* const kCrease[] = {"uniform", "chaikin"};
const char* const kTri[] = {"catmark", "smooth"};

int lookup(const char* const* names, int n, const std::string& v, const std::string& opt) {
    for (int i = 0; i < n; ++i)
        if (v == names[i]) return i;
    fail("bad value '" + v + "' for " + opt);
}

Settings parse_args(int argc, char** argv) {
    Settings s;
    std::vector<std::string> pos;
    bool scheme_given = false;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) fail("missing value for " + a);
            return argv[++i];
        };
        if (a == "--scheme") {
            std::string v = value();
            if (v == "catmark") s.scheme = Sdc::SCHEME_CATMARK;
            else if (v == "loop") s.scheme = Sdc::SCHEME_LOOP;
            else fail("bad scheme '" + v + "' (catmark|loop)");
            scheme_given = true;
        } else if (a == "--levels") {
            long l;
            if (!parse_long(value(), l) || l < 0 || l > 10) fail("--levels needs an integer 0..10");
            s.levels = static_cast<int>(l);
        } else if (a == "--boundary") {
            s.boundary = lookup(kBoundary, 3, value(), a);
        } else if (a == "--fvar") {
            s.fvar = lookup(kFvar, 6, value(), a);
        } else if (a == "--crease-method") {
            s.crease = lookup(kCrease, 2, value(), a);
        } else if (a == "--smooth-triangles") {
            s.tri = 1;
        } else if (a == "--limit") {
            s.limit = true;
        } else if (a == "--dump") {
            s.dump = value();
        } else if (!a.empty() && a[0] == '-') {
            fail("unknown option " + a);
        } else {
            pos.push_back(a);
        }
    }
    if (!scheme_given || s.levels < 0 || pos.size() != 2)
        fail("usage: osd_refine --scheme catmark|loop --levels L [--boundary B] [--fvar F] "
             "[--crease-method M] [--smooth-triangles] [--limit] [--dump FILE] IN.obj OUT.txt");
    s.in = pos[0];
    s.out = pos[1];
    return s;
}

// Options from tags, then the command line on top.
Sdc::Options make_options(Settings const& s, Net const& net) {
    int boundary = 2, fvar = 5, crease = 0, tri = 0;
    for (Tag const& t : net.tags) {
        const std::string where = "line " + std::to_string(t.line) + ": tag " + t.name + ": ";
        if (t.name == "interpolateboundary") {
            if (t.ints.size() != 1) fail(where + "expects 1 integer");
            switch (t.ints[0]) {
                case 0: boundary = 0; break;
                case 1: boundary = 2; break;
                case 2: boundary = 1; break;
                default: fail(where + "value must be 0, 1 or 2");
            }
        } else if (t.name == "facevaryinginterpolateboundary") {
            if (t.ints.size() != 1 || t.ints[0] < 0 || t.ints[0] > 5) fail(where + "expects 1 integer 0..5");
            fvar = static_cast<int>(t.ints[0]);
        } else if (t.name == "facevaryingpropagatecorners") {
            warn(where + "ignored (OpenSubdiv 3 has no such option)");
        } else if (t.name == "creasemethod") {
            if (t.strings.size() != 1) fail(where + "expects 1 string");
            if (t.strings[0] == "normal" || t.strings[0] == "uniform") crease = 0;
            else if (t.strings[0] == "chaikin") crease = 1;
            else fail(where + "value must be normal or chaikin");
        } else if (t.name == "smoothtriangles") {
            int v = -1;
            if (t.strings.size() == 1 && t.ints.empty()) {
                if (t.strings[0] == "catmark") v = 0;
                else if (t.strings[0] == "smooth") v = 1;
            } else if (t.ints.size() == 1 && t.strings.empty() && (t.ints[0] == 0 || t.ints[0] == 1)) {
                v = static_cast<int>(t.ints[0]);
            }
            if (v < 0) fail(where + "expects catmark or smooth");
            if (s.scheme != Sdc::SCHEME_CATMARK) warn(where + "applies to Catmark only; ignored");
            else tri = v;
        } else if (t.name == "crease" || t.name == "corner" || t.name == "hole") {
            // component tags, handled in make_descriptor
        } else {
            warn(where + "not supported; ignored");
        }
    }
    if (s.boundary >= 0) boundary = s.boundary;
    if (s.fvar >= 0) fvar = s.fvar;
    if (s.crease >= 0) crease = s.crease;
    if (s.tri >= 0) {
        if (s.scheme != Sdc::SCHEME_CATMARK) warn("--smooth-triangles applies to Catmark only; ignored");
        else tri = s.tri;
    }
    Sdc::Options o;
    o.SetVtxBoundaryInterpolation(static_cast<Sdc::Options::VtxBoundaryInterpolation>(boundary));
    o.SetFVarLinearInterpolation(static_cast<Sdc::Options::FVarLinearInterpolation>(fvar));
    o.SetCreasingMethod(static_cast<Sdc::Options::CreasingMethod>(crease));
    o.SetTriangleSubdivision(static_cast<Sdc::Options::TriangleSubdivision>(tri));
    return o;
}

// Component tags, checked against the net: every crease pair must be an edge of some face.
struct Components {
    std::vector<int> crease_pairs;
    std::vector<float> crease_w;
    std::vector<int> corner_v;
    std::vector<float> corner_w;
    std::vector<int> holes;
};

Components make_components(Net const& net) {
    std::set<std::pair<int, int>> edges;
    for (size_t f = 0, o = 0; f < net.face_sizes.size(); o += net.face_sizes[f], ++f) {
        int n = net.face_sizes[f];
        for (int i = 0; i < n; ++i) {
            int a = net.corners[o + i], b = net.corners[o + (i + 1) % n];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }
    Components c;
    const long nv = static_cast<long>(net.points.size());
    const long nf = static_cast<long>(net.face_sizes.size());
    for (Tag const& t : net.tags) {
        const std::string where = "line " + std::to_string(t.line) + ": tag " + t.name + ": ";
        if (t.name == "crease") {
            if (t.ints.size() < 2 || t.ints.size() % 2) fail(where + "expects vertex pairs");
            size_t pairs = t.ints.size() / 2;
            if (t.floats.size() != 1 && t.floats.size() != pairs)
                fail(where + "expects 1 sharpness or one per vertex pair");
            for (size_t k = 0; k < pairs; ++k) {
                long a = t.ints[2 * k], b = t.ints[2 * k + 1];
                if (a < 0 || a >= nv || b < 0 || b >= nv) fail(where + "vertex out of range");
                if (!edges.count({std::min(a, b), std::max(a, b)}))
                    fail(where + "no edge between vertices " + std::to_string(a) + " and " + std::to_string(b));
                c.crease_pairs.push_back(static_cast<int>(a));
                c.crease_pairs.push_back(static_cast<int>(b));
                double w = t.floats.size() == 1 ? t.floats[0] : t.floats[k];
                c.crease_w.push_back(static_cast<float>(std::max(0.0, w)));
            }
        } else if (t.name == "corner") {
            if (t.ints.empty()) fail(where + "expects vertices");
            if (t.floats.size() != 1 && t.floats.size() != t.ints.size())
                fail(where + "expects 1 sharpness or one per vertex");
            for (size_t k = 0; k < t.ints.size(); ++k) {
                if (t.ints[k] < 0 || t.ints[k] >= nv) fail(where + "vertex " + std::to_string(t.ints[k]) + " out of range");
                c.corner_v.push_back(static_cast<int>(t.ints[k]));
                double w = t.floats.size() == 1 ? t.floats[0] : t.floats[k];
                c.corner_w.push_back(static_cast<float>(std::max(0.0, w)));
            }
        } else if (t.name == "hole") {
            for (long f : t.ints) {
                if (f < 0 || f >= nf) fail(where + "face " + std::to_string(f) + " out of range");
                c.holes.push_back(static_cast<int>(f));
            }
        }
    }
    return c;
}

const char* rule_name(Sdc::Crease::Rule r) {
    switch (r) {
        case Sdc::Crease::RULE_SMOOTH: return "smooth";
        case Sdc::Crease::RULE_DART: return "dart";
        case Sdc::Crease::RULE_CREASE: return "crease";
        case Sdc::Crease::RULE_CORNER: return "corner";
        default: return "unknown";
    }
}

void put3(FILE* f, const char* key, double const* x) {
    std::fprintf(f, "%s %.17g %.17g %.17g", key, x[0], x[1], x[2]);
}

}  // namespace

int main(int argc, char** argv) {
    Settings s = parse_args(argc, argv);
    Net net = read_obj(s.in.c_str());
    Sdc::Options opts = make_options(s, net);
    Components comp = make_components(net);
    const bool has_uv = net.faces_with_uv > 0;

    Far::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(net.points.size());
    desc.numFaces = static_cast<int>(net.face_sizes.size());
    desc.numVertsPerFace = net.face_sizes.data();
    desc.vertIndicesPerFace = net.corners.data();
    desc.numCreases = static_cast<int>(comp.crease_w.size());
    desc.creaseVertexIndexPairs = comp.crease_pairs.data();
    desc.creaseWeights = comp.crease_w.data();
    desc.numCorners = static_cast<int>(comp.corner_w.size());
    desc.cornerVertexIndices = comp.corner_v.data();
    desc.cornerWeights = comp.corner_w.data();
    desc.numHoles = static_cast<int>(comp.holes.size());
    desc.holeIndices = comp.holes.data();
    Far::TopologyDescriptor::FVarChannel channel;
    if (has_uv) {
        channel.numValues = static_cast<int>(net.uvs.size());
        channel.valueIndices = net.uv_corners.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &channel;
    }

    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(s.scheme, opts)));
    if (!refiner) fail("OpenSubdiv rejected the net (see its message above)");
    Far::TopologyRefiner::UniformOptions uo(s.levels);
    uo.fullTopologyInLastLevel = true;  // Limit() needs the last level's vertex-edge relations
    refiner->RefineUniform(uo);
    const int L = refiner->GetMaxLevel();

    // Level-by-level interpolation in double precision.
    Far::PrimvarRefinerReal<double> pr(*refiner);
    std::vector<std::vector<P3>> pts(L + 1);
    std::vector<std::vector<P2>> uvs(L + 1);
    pts[0] = net.points;
    if (has_uv) uvs[0] = net.uvs;
    for (int l = 1; l <= L; ++l) {
        pts[l].resize(refiner->GetLevel(l).GetNumVertices());
        pr.Interpolate(l, pts[l - 1], pts[l]);
        if (has_uv) {
            uvs[l].resize(refiner->GetLevel(l).GetNumFVarValues(0));
            pr.InterpolateFaceVarying(l, uvs[l - 1], uvs[l], 0);
        }
    }

    Far::TopologyLevel const& last = refiner->GetLevel(L);
    const int nv = last.GetNumVertices(), nf = last.GetNumFaces();
    const int nu = has_uv ? last.GetNumFVarValues(0) : 0;
    int holes = 0;
    for (int f = 0; f < nf; ++f) holes += last.IsFaceHole(f);

    std::vector<P3> lp, lt1, lt2;
    std::vector<P2> luv;
    if (s.limit) {
        lp.resize(nv);
        lt1.resize(nv);
        lt2.resize(nv);
        pr.Limit(pts[L], lp, lt1, lt2);
        if (has_uv) {
            luv.resize(nu);
            pr.LimitFaceVarying(uvs[L], luv, 0);
        }
    }

    FILE* out = std::fopen(s.out.c_str(), "w");
    if (!out) fail("cannot create " + s.out);
    std::fprintf(out, "osd_refine 1\nscheme %s\nlevels %d\n", s.scheme == Sdc::SCHEME_LOOP ? "loop" : "catmark", L);
    std::fprintf(out, "boundary %s\nfvar %s\ncrease-method %s\ntriangles %s\n",
                 kBoundary[opts.GetVtxBoundaryInterpolation()], kFvar[opts.GetFVarLinearInterpolation()],
                 kCrease[opts.GetCreasingMethod()], kTri[opts.GetTriangleSubdivision()]);
    std::fprintf(out, "vertices %d\nfaces %d\nholes %d\nfvar-values %d\nlimit %d\n", nv, nf, holes, nu,
                 s.limit ? 1 : 0);
    for (int v = 0; v < nv; ++v) {
        put3(out, "v", pts[L][v].x);
        std::fputc('\n', out);
    }
    for (int f = 0; f < nf; ++f) {
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        std::fprintf(out, "f %d", last.IsFaceHole(f) ? 1 : 0);
        for (int i = 0; i < fv.size(); ++i) std::fprintf(out, " %d", fv[i]);
        std::fputc('\n', out);
    }
    if (has_uv) {
        for (int u = 0; u < nu; ++u) std::fprintf(out, "vt %.17g %.17g\n", uvs[L][u].x[0], uvs[L][u].x[1]);
        for (int f = 0; f < nf; ++f) {
            Far::ConstIndexArray fu = last.GetFaceFVarValues(f, 0);
            std::fprintf(out, "fv");
            for (int i = 0; i < fu.size(); ++i) std::fprintf(out, " %d", fu[i]);
            std::fputc('\n', out);
        }
    }
    if (s.limit) {
        for (int v = 0; v < nv; ++v) {
            put3(out, "lp", lp[v].x);
            std::fputc('\n', out);
        }
        for (int v = 0; v < nv; ++v) {
            put3(out, "lt", lt1[v].x);
            std::fprintf(out, " %.17g %.17g %.17g\n", lt2[v].x[0], lt2[v].x[1], lt2[v].x[2]);
        }
        for (int u = 0; u < nu; ++u) std::fprintf(out, "lvt %.17g %.17g\n", luv[u].x[0], luv[u].x[1]);
    }
    std::fprintf(out, "end\n");
    if (std::fclose(out) != 0) fail("cannot write " + s.out);

    if (!s.dump.empty()) {
        FILE* d = std::fopen(s.dump.c_str(), "w");
        if (!d) fail("cannot create " + s.dump);
        for (int l = 0; l <= L; ++l) {
            Far::TopologyLevel const& lv = refiner->GetLevel(l);
            std::fprintf(d, "level %d vertices %d edges %d faces %d\n", l, lv.GetNumVertices(), lv.GetNumEdges(),
                         lv.GetNumFaces());
            for (int v = 0; v < lv.GetNumVertices(); ++v) {
                std::fprintf(d, "v %d", v);
                std::fprintf(d, " %.17g %.17g %.17g", pts[l][v].x[0], pts[l][v].x[1], pts[l][v].x[2]);
                std::fprintf(d, " sharp %.9g rule %s faces %d edges %d%s%s\n", lv.GetVertexSharpness(v),
                             rule_name(lv.GetVertexRule(v)), lv.GetVertexFaces(v).size(), lv.GetVertexEdges(v).size(),
                             lv.IsVertexBoundary(v) ? " boundary" : "", lv.IsVertexNonManifold(v) ? " nonmanifold" : "");
            }
            for (int e = 0; e < lv.GetNumEdges(); ++e) {
                Far::ConstIndexArray ev = lv.GetEdgeVertices(e);
                std::fprintf(d, "e %d %d %d sharp %.9g faces %d%s\n", e, ev[0], ev[1], lv.GetEdgeSharpness(e),
                             lv.GetEdgeFaces(e).size(), lv.IsEdgeNonManifold(e) ? " nonmanifold" : "");
            }
            for (int f = 0; f < lv.GetNumFaces(); ++f) {
                Far::ConstIndexArray fv = lv.GetFaceVertices(f);
                std::fprintf(d, "f %d", f);
                for (int i = 0; i < fv.size(); ++i) std::fprintf(d, " %d", fv[i]);
                std::fprintf(d, "%s\n", lv.IsFaceHole(f) ? " hole" : "");
            }
            if (has_uv) {
                for (int u = 0; u < lv.GetNumFVarValues(0); ++u)
                    std::fprintf(d, "vt %d %.17g %.17g\n", u, uvs[l][u].x[0], uvs[l][u].x[1]);
                for (int f = 0; f < lv.GetNumFaces(); ++f) {
                    Far::ConstIndexArray fu = lv.GetFaceFVarValues(f, 0);
                    std::fprintf(d, "fv %d", f);
                    for (int i = 0; i < fu.size(); ++i) std::fprintf(d, " %d", fu[i]);
                    std::fputc('\n', d);
                }
            }
        }
        if (std::fclose(d) != 0) fail("cannot write " + s.dump);
    }
    return 0;
}
