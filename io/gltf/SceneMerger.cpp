#include "io/gltf/SceneMerger.h"

#include "io/ReadFailure.h"
#include "io/gltf/GltfAccessors.h"
#include "io/mesh/PositionWelder.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>

namespace wisp::io::gltf {

namespace {

// Many nodes can instance one big mesh; the merged mesh must still fit in memory (~1.2 GB).
constexpr std::size_t maxTriangles = 50'000'000;

// A node's transform relative to its parent: its matrix, or translation * rotation * scale.
glm::dmat4 localTransform(const Node& node, std::size_t nodeIndex)
{
    const std::string location = indexed("nodes", nodeIndex);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16)
            fail(location, "matrix has " + plural(node.matrix.size(), "number", "numbers") + "; a matrix has 16");
        glm::dmat4 m(1.0);
        for (int column = 0; column < 4; ++column) // glTF and GLM both store column after column
            for (int row = 0; row < 4; ++row)
                m[column][row] = node.matrix[static_cast<std::size_t>(column * 4 + row)];
        return m;
    }
    glm::dmat4 m(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3)
            fail(location, "translation has " + plural(node.translation.size(), "number", "numbers") + "; it needs 3");
        m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4)
            fail(location,
                "rotation has " + plural(node.rotation.size(), "number", "numbers") + "; a quaternion needs 4");
        double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
        const double norm = std::sqrt(x * x + y * y + z * z + w * w);
        if (!(norm > 1e-12) || !std::isfinite(norm))
            fail(location, "rotation is not a rotation (its quaternion has length " + std::to_string(norm) + ")");
        // Exporters write unit quaternions to float precision; normalise so that rounding does
        // not scale the head.
        x /= norm, y /= norm, z /= norm, w /= norm;
        const glm::dmat3 r(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), // column 0
            2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), // column 1
            2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)); // column 2
        for (int c = 0; c < 3; ++c)
            m[c] = glm::dvec4(r[c], 0.0);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3)
            fail(location, "scale has " + plural(node.scale.size(), "number", "numbers") + "; it needs 3");
        for (int c = 0; c < 3; ++c)
            m[c] *= node.scale[static_cast<std::size_t>(c)];
    }
    return m;
}

class SceneMerger {
public:
    SceneMerger(const Document& model, std::vector<std::string>& warnings)
        : m_model(model)
        , m_warnings(warnings)
    {
    }

    TriangleMesh take()
    {
        addScene();
        reportSkipped();
        if (m_mesh.triangles.empty())
            fail({}, "no triangles: " + whyNoTriangles());
        return std::move(m_mesh);
    }

private:
    struct Pending {
        int node;
        int parent; // -1 for a root
        glm::dmat4 parentWorld;
    };

    void addScene()
    {
        const std::vector<Scene>& scenes = m_model.scenes;
        std::vector<int> roots;
        std::string rootsLocation;
        if (m_model.defaultScene >= 0) {
            if (static_cast<std::size_t>(m_model.defaultScene) >= scenes.size())
                fail("scene",
                    "the default scene is scenes[" + std::to_string(m_model.defaultScene) + "], but the file has "
                        + plural(scenes.size(), "scene", "scenes"));
            roots = scenes[static_cast<std::size_t>(m_model.defaultScene)].nodes;
            rootsLocation = indexed("scenes", static_cast<std::size_t>(m_model.defaultScene)) + ".nodes";
        } else if (!scenes.empty()) {
            // The spec leaves the choice to the reader when no default scene is named.
            if (scenes.size() > 1)
                m_warnings.push_back(
                    "the file names no default scene; read scenes[0], the first of " + std::to_string(scenes.size()));
            roots = scenes.front().nodes;
            rootsLocation = "scenes[0].nodes";
        } else {
            // No scenes at all: every node that is nobody's child is a root.
            std::vector<char> isChild(m_model.nodes.size(), 0);
            for (const Node& node : m_model.nodes)
                for (int child : node.children)
                    if (child >= 0 && static_cast<std::size_t>(child) < isChild.size())
                        isChild[static_cast<std::size_t>(child)] = 1;
            for (std::size_t i = 0; i < m_model.nodes.size(); ++i)
                if (!isChild[i])
                    roots.push_back(static_cast<int>(i));
            rootsLocation = "nodes";
        }

        // Iterative, so that a deep (or corrupt) hierarchy cannot overflow the stack. Each node
        // may be reached once: glTF nodes form trees, and a node reached twice (a cycle, or two
        // parents) would loop forever or multiply the mesh.
        std::vector<char> reached(m_model.nodes.size(), 0);
        std::vector<Pending> pending;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it)
            pending.push_back({ *it, -1, glm::dmat4(1.0) });
        while (!pending.empty()) {
            const Pending next = pending.back();
            pending.pop_back();
            if (next.node < 0 || static_cast<std::size_t>(next.node) >= m_model.nodes.size())
                fail(next.parent < 0 ? rootsLocation
                                     : indexed("nodes", static_cast<std::size_t>(next.parent)) + ".children",
                    "names nodes[" + std::to_string(next.node) + "], but the file has "
                        + plural(m_model.nodes.size(), "node", "nodes"));
            const auto nodeIndex = static_cast<std::size_t>(next.node);
            if (reached[nodeIndex])
                fail(indexed("nodes", nodeIndex),
                    "is reached twice in the node hierarchy (it has two parents, is listed twice, "
                    "or is its own ancestor); glTF nodes must form trees");
            reached[nodeIndex] = 1;
            const Node& node = m_model.nodes[nodeIndex];
            const glm::dmat4 world = next.parentWorld * localTransform(node, nodeIndex);
            if (node.mesh >= 0) {
                if (static_cast<std::size_t>(node.mesh) >= m_model.meshes.size())
                    fail(indexed("nodes", nodeIndex),
                        "names meshes[" + std::to_string(node.mesh) + "], but the file has "
                            + plural(m_model.meshes.size(), "mesh", "meshes"));
                // A skinned mesh's vertices are placed by its joints, and the spec says to
                // ignore the transform of the node that holds it; without animation the joints
                // rest in the bind pose, where the vertices already are.
                addMeshInstance(nodeIndex, node.skin >= 0 ? glm::dmat4(1.0) : world);
            }
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
                pending.push_back({ *it, next.node, world });
        }
    }

    void addMeshInstance(std::size_t nodeIndex, const glm::dmat4& world)
    {
        ++m_meshInstances;
        const Node& node = m_model.nodes[nodeIndex];
        const auto meshIndex = static_cast<std::size_t>(node.mesh);
        const Mesh& mesh = m_model.meshes[meshIndex];
        // A node may override its mesh's default morph weights.
        const std::vector<double>& weights = node.weights.empty() ? mesh.weights : node.weights;
        // A mirroring transform turns counter-clockwise triangles clockwise; swapping two corners
        // turns them back (the spec asks renderers to do the same).
        const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
        // Output vertex of each POSITION element, per accessor, for this instance: primitives that
        // share an accessor share vertices, and unused elements are not copied.
        std::map<int, std::vector<std::uint32_t>> sharedVertices;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
            addPrimitive(meshIndex, p, nodeIndex, world, mirrored, weights, sharedVertices);
    }

    const std::vector<double>& positionsOf(int accessor, const std::string& use)
    {
        auto it = m_positions.find(accessor);
        if (it != m_positions.end())
            return it->second;
        AccessorValues values = readAccessor(m_model, accessor, use);
        if (values.components != 3)
            fail(indexed("accessors", static_cast<std::size_t>(accessor)) + " (" + use + ")",
                "is " + m_model.accessors[static_cast<std::size_t>(accessor)].type + "; positions are VEC3");
        for (std::size_t i = 0; i < values.values.size(); ++i)
            if (!std::isfinite(values.values[i]))
                fail(indexed("accessors", static_cast<std::size_t>(accessor)) + " (" + use + ")",
                    "element " + std::to_string(i / 3) + " is not a finite number");
        return m_positions.emplace(accessor, std::move(values.values)).first->second;
    }

    void addPrimitive(std::size_t meshIndex, std::size_t primitiveIndex, std::size_t nodeIndex, const glm::dmat4& world,
        bool mirrored, const std::vector<double>& weights, std::map<int, std::vector<std::uint32_t>>& sharedVertices)
    {
        const Primitive& primitive = m_model.meshes[meshIndex].primitives[primitiveIndex];
        const std::string location = indexed("meshes", meshIndex) + "." + indexed("primitives", primitiveIndex);
        const int mode = primitive.mode;
        if (mode >= mode::Points && mode <= mode::LineStrip) {
            ++m_pointAndLinePrimitives;
            return;
        }
        if (mode != mode::Triangles && mode != mode::TriangleStrip && mode != mode::TriangleFan)
            fail(location, "mode " + std::to_string(mode) + " is not a glTF primitive mode (0 to 6)");
        const auto positionAttribute = primitive.attributes.find("POSITION");
        if (positionAttribute == primitive.attributes.end()) {
            ++m_primitivesWithoutPositions;
            return;
        }
        ++m_trianglePrimitives;

        const int positionAccessor = positionAttribute->second;
        const std::vector<double>* positions = &positionsOf(positionAccessor, "POSITION of " + location);
        const std::size_t vertexCount = positions->size() / 3;

        // Morph targets move the vertices by their default weights; a morphed primitive gets
        // its own vertices.
        std::vector<double> morphed;
        for (std::size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t) {
            const auto target = primitive.targets[t].find("POSITION");
            if (target == primitive.targets[t].end() || weights[t] == 0.0)
                continue;
            const std::string use = "POSITION of " + location + ".targets[" + std::to_string(t) + "]";
            const std::vector<double>& offsets = positionsOf(target->second, use);
            if (offsets.size() != positions->size())
                fail(location,
                    "morph target " + std::to_string(t) + " moves " + plural(offsets.size() / 3, "vertex", "vertices")
                        + ", but the primitive has " + std::to_string(vertexCount));
            if (morphed.empty())
                morphed = *positions;
            for (std::size_t i = 0; i < morphed.size(); ++i)
                morphed[i] += weights[t] * offsets[i];
        }
        std::vector<std::uint32_t> ownVertices;
        std::vector<std::uint32_t>* outputVertex = &ownVertices;
        if (!morphed.empty())
            positions = &morphed;
        else
            outputVertex = &sharedVertices[positionAccessor];
        if (outputVertex->empty())
            outputVertex->assign(vertexCount, unassigned);

        // Indices, or 0, 1, 2, ... when the primitive has none.
        std::vector<std::uint32_t> indices;
        if (primitive.indices >= 0) {
            const std::string use = "indices of " + location;
            if (static_cast<std::size_t>(primitive.indices) < m_model.accessors.size()) {
                const Accessor& accessor = m_model.accessors[static_cast<std::size_t>(primitive.indices)];
                const int type = accessor.componentType;
                if (type != component::UnsignedByte && type != component::UnsignedShort
                    && type != component::UnsignedInt)
                    fail(indexed("accessors", static_cast<std::size_t>(primitive.indices)) + " (" + use + ")",
                        std::string("indices are ") + componentTypeName(type)
                            + "; they must be unsigned bytes, shorts or ints");
                if (accessor.type != "SCALAR" || accessor.normalized)
                    fail(indexed("accessors", static_cast<std::size_t>(primitive.indices)) + " (" + use + ")",
                        "indices must be SCALAR and not normalized");
            }
            const AccessorValues values = readAccessor(m_model, primitive.indices, use);
            indices.resize(values.values.size());
            for (std::size_t i = 0; i < indices.size(); ++i) {
                const double v = values.values[i];
                if (v >= static_cast<double>(vertexCount))
                    fail(location,
                        "index " + std::to_string(i) + " is " + std::to_string(static_cast<std::uint64_t>(v))
                            + ", out of range: the POSITION accessor has " + plural(vertexCount, "vertex", "vertices"));
                indices[i] = static_cast<std::uint32_t>(v);
            }
        } else {
            if (vertexCount > std::numeric_limits<std::uint32_t>::max())
                fail(location, "has more vertices than 32-bit indices can number");
            indices.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i)
                indices[i] = static_cast<std::uint32_t>(i);
        }

        const std::size_t n = indices.size();
        // Where a vertex of this primitive lands, as it will be stored; computed once per
        // instance.
        auto landed = [&](std::uint32_t local) -> glm::vec3 {
            const std::uint32_t out = (*outputVertex)[local];
            if (out != unassigned)
                return m_mesh.positions[out];
            const glm::dvec4 p = world
                * glm::dvec4((*positions)[3 * local], (*positions)[3 * local + 1], (*positions)[3 * local + 2], 1.0);
            // + 0.0f turns -0 into +0, so that welding sees one zero.
            const glm::vec3 stored
                = glm::vec3(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)) + 0.0f;
            if (!std::isfinite(stored.x) || !std::isfinite(stored.y) || !std::isfinite(stored.z))
                fail(indexed("nodes", nodeIndex),
                    "its transform takes vertex " + std::to_string(local) + " of " + location
                        + " beyond the range of numbers (not finite)");
            return stored;
        };
        auto corner = [&](std::uint32_t local, const glm::vec3& at) -> std::uint32_t {
            std::uint32_t& out = (*outputVertex)[local];
            if (out == unassigned)
                out = weld(at);
            return out;
        };
        auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, bool reportDegenerate) {
            // Strips repeat a vertex on purpose to join runs; elsewhere a triangle without three
            // distinct corners (by index, or by position once welded) is worth a remark.
            if (a == b || b == c || a == c) {
                if (reportDegenerate)
                    ++m_degenerateTriangles;
                return;
            }
            const glm::vec3 atA = landed(a), atB = landed(b), atC = landed(c);
            if (atA == atB || atB == atC || atA == atC) {
                if (reportDegenerate)
                    ++m_degenerateTriangles;
                return;
            }
            if (m_mesh.triangles.size() >= maxTriangles)
                fail({},
                    "more than " + std::to_string(maxTriangles)
                        + " triangles; a head mesh needs far fewer (decimate it)");
            const std::uint32_t outA = corner(a, atA), outB = corner(b, atB), outC = corner(c, atC);
            m_mesh.triangles.push_back(mirrored ? glm::uvec3(outA, outC, outB) : glm::uvec3(outA, outB, outC));
        };

        if (mode == mode::Triangles) {
            for (std::size_t i = 0; i + 2 < n; i += 3)
                emit(indices[i], indices[i + 1], indices[i + 2], true);
            if (n % 3 != 0)
                ++m_primitivesWithLeftoverIndices;
        } else if (mode == mode::TriangleStrip) {
            // The spec's strip: triangle i is (i, i + 1 + i % 2, i + 2 - i % 2), so that every
            // other triangle is flipped back to the same winding.
            for (std::size_t i = 0; i + 2 < n; ++i)
                emit(indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2], false);
        } else {
            // The spec's fan: triangle i is (i + 1, i + 2, 0).
            for (std::size_t i = 0; i + 2 < n; ++i)
                emit(indices[i + 1], indices[i + 2], indices[0], true);
        }
    }

    // The output vertex at `at`, shared by every corner at bit-identical coordinates.
    std::uint32_t weld(const glm::vec3& at) { return m_welder.indexOf(at, m_mesh.positions); }

    void reportSkipped()
    {
        if (m_pointAndLinePrimitives > 0)
            m_warnings.push_back("skipped " + plural(m_pointAndLinePrimitives, "primitive", "primitives")
                + " of points or lines, which are not a surface");
        if (m_primitivesWithoutPositions > 0)
            m_warnings.push_back("skipped " + plural(m_primitivesWithoutPositions, "primitive", "primitives")
                + " without a POSITION attribute");
        if (m_degenerateTriangles > 0)
            m_warnings.push_back("skipped " + plural(m_degenerateTriangles, "triangle", "triangles")
                + " with fewer than 3 distinct corners");
        if (m_primitivesWithLeftoverIndices > 0)
            m_warnings.push_back("ignored the last one or two indices of "
                + plural(m_primitivesWithLeftoverIndices, "primitive", "primitives")
                + ", which make no whole triangle");
    }

    std::string whyNoTriangles() const
    {
        if (m_model.meshes.empty())
            return "the file holds no meshes";
        if (m_meshInstances == 0)
            return "no node of the scene places any of the file's " + plural(m_model.meshes.size(), "mesh", "meshes");
        if (m_trianglePrimitives == 0 && m_pointAndLinePrimitives > 0)
            return "the scene's meshes hold only points and lines, which are not a surface";
        if (m_trianglePrimitives == 0 && m_primitivesWithoutPositions > 0)
            return "the scene's primitives have no POSITION attribute";
        if (m_degenerateTriangles > 0)
            return "every triangle repeats a vertex";
        return "the scene's triangle primitives are empty";
    }

    static constexpr std::uint32_t unassigned = std::numeric_limits<std::uint32_t>::max();

    const Document& m_model;
    std::vector<std::string>& m_warnings;
    TriangleMesh m_mesh;
    std::map<int, std::vector<double>> m_positions; // decoded POSITION accessors, in the file's space
    mesh::PositionWelder m_welder; // output vertex at each position
    std::size_t m_meshInstances = 0;
    std::size_t m_trianglePrimitives = 0;
    std::size_t m_pointAndLinePrimitives = 0;
    std::size_t m_primitivesWithoutPositions = 0;
    std::size_t m_primitivesWithLeftoverIndices = 0;
    std::size_t m_degenerateTriangles = 0;
};

} // namespace

TriangleMesh mergeScene(const Document& model, std::vector<std::string>& warnings)
{
    return SceneMerger(model, warnings).take();
}

} // namespace wisp::io::gltf
