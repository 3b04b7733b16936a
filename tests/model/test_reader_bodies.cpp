// The bodies and torques sections (docs/theory.md §4.4): inertia forms, initial orientations, posed
// bodies, body points everywhere a point is accepted, and errors at file:line:column.

#include <gtest/gtest.h>

#include <cmath>

#include "lagrange/reader.hpp"
#include "lagrange/rigid_body.hpp"
#include "support/ginac_values.hpp"

namespace lagrange {
namespace {

double value(const Model& m, const GiNaC::ex& e) {
  GiNaC::exmap values;
  for (const auto& p : m.parameters) values[p.sym] = p.value;
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(values).evalf()).to_double();
}

const std::string kFree = R"(parameters: {m: 2, a: 0.3, b: 0.2, c: 0.1}
bodies:
  brick:
    mass: m
    shape: {box: [a, b, c]}
    com: [0, 0, c/2]
    frame: free
    initial:
      position: [1, 2, 3]
      orientation: {axis_angle: {axis: [0, 0, 2], angle: pi/2}}
      velocity: [0.5, 0, 0]
      omega: [0, 5, 0]
    points:
      corner: [a/2, b/2, c/2]
)";

TEST(ReaderBodies, FreeBodyWithShapeAndInitialState) {
  const Model m = read_model_string(kFree, "m.yaml");
  ASSERT_EQ(m.bodies.size(), 1u);
  const Body& b = m.bodies[0];
  EXPECT_TRUE(b.free);
  EXPECT_TRUE(m.coordinates.empty());
  // Box: I_xx = m(b² + c²)/12 and cyclic (docs/theory.md §4.8).
  EXPECT_NEAR(value(m, b.inertia[0][0]), 2 * (0.04 + 0.01) / 12, 1e-15);
  EXPECT_NEAR(value(m, b.inertia[1][1]), 2 * (0.09 + 0.01) / 12, 1e-15);
  EXPECT_NEAR(value(m, b.inertia[2][2]), 2 * (0.09 + 0.04) / 12, 1e-15);
  EXPECT_NEAR(value(m, b.com[2]), 0.05, 1e-15);
  EXPECT_EQ(b.r0, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(b.v0, (std::array<double, 3>{0.5, 0, 0}));
  EXPECT_EQ(b.w0, (std::array<double, 3>{0, 5, 0}));
  const Rotation expected{0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (size_t k = 0; k < 9; ++k) EXPECT_NEAR(b.R0[k], expected[k], 1e-15) << k;
  // The body point is r + R p_b in the world frame.
  const Point* p = m.find_point("brick.corner");
  ASSERT_NE(p, nullptr);
  const Vec3 w =
      b.world_point({m.parameters[1].sym / 2, m.parameters[2].sym / 2, m.parameters[3].sym / 2});
  for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(same(p->pos[k], w[k]));
}

TEST(ReaderBodies, OrientationFormsAgree) {
  auto orientation = [](const std::string& form) {
    const Model m = read_model_string(
        "bodies:\n  b:\n    mass: 1\n    inertia: [1, 1, 1]\n    frame: free\n    initial: "
        "{orientation: " +
            form + "}\n",
        "o.yaml");
    return m.bodies[0].R0;
  };
  // 90° about z, then the same written four ways; Euler angles are [roll, pitch, yaw] with
  // R = R_z(yaw) R_y(pitch) R_x(roll).
  const Rotation a = orientation("{axis_angle: {axis: [0, 0, 1], angle: pi/2}}");
  const Rotation forms[] = {orientation("{euler: [0, 0, pi/2]}"),
                            orientation("{quaternion: [sqrt(1/2), 0, 0, sqrt(1/2)]}"),
                            orientation("{matrix: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]}"),
                            orientation("{matrix: rot_z(pi/2)}")};
  for (const Rotation& f : forms)
    for (size_t k = 0; k < 9; ++k) EXPECT_NEAR(f[k], a[k], 1e-15) << k;
  const Rotation e = orientation("{euler: [0.1, 0.2, 0.3]}");
  const Rotation r = rotation_from_euler(0.1, 0.2, 0.3);
  for (size_t k = 0; k < 9; ++k) EXPECT_EQ(e[k], r[k]);
}

TEST(ReaderBodies, InertiaForms) {
  auto inertia = [](const std::string& spec) {
    const Model m =
        read_model_string("parameters: {r: 0.5, h: 2}\nbodies:\n  b:\n    mass: 3\n    " + spec +
                              "\n    frame: free\n    initial: {}\n",
                          "i.yaml");
    std::array<double, 9> out{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) out[3 * i + j] = value(m, m.bodies[0].inertia[i][j]);
    return out;
  };
  EXPECT_EQ(inertia("inertia: [1, 2, 2.5]"), (std::array<double, 9>{1, 0, 0, 0, 2, 0, 0, 0, 2.5}));
  EXPECT_EQ(inertia("inertia: [[2, 0.1, 0], [0.1, 2, 0], [0, 0, 3]]"),
            (std::array<double, 9>{2, 0.1, 0, 0.1, 2, 0, 0, 0, 3}));
  // Cylinder along z: I_zz = m r²/2, I_xx = I_yy = m(3r² + h²)/12; sphere 2/5 m r².
  const auto cyl = inertia("shape: {cylinder: {radius: r, length: h}}");
  EXPECT_NEAR(cyl[8], 3 * 0.25 / 2, 1e-15);
  EXPECT_NEAR(cyl[0], 3 * (0.75 + 4) / 12, 1e-15);
  EXPECT_NEAR(cyl[4], cyl[0], 1e-15);
  const auto sph = inertia("shape: {sphere: {radius: r}}");
  EXPECT_NEAR(sph[0], 0.4 * 3 * 0.25, 1e-15);
  EXPECT_NEAR(sph[8], sph[0], 1e-15);
}

// A posed link built on an earlier one, body points in particles, springs, dampers, forces
// (world and body frame), potentials, constraints and outputs, vector constraints by component.
TEST(ReaderBodies, PosedBodiesAndBodyPointsEverywhere) {
  const std::string yaml = R"(parameters: {l: 1, k: 10, F: 2}
coordinates:
  q1: {initial: 0.1}
  q2: {initial: 0.2}
bodies:
  link1:
    mass: 1
    inertia: [0.1, 0.1, 0.1]
    position: [0, 0, 0]
    rotation: rot_z(q1)
    points: {tip: [l, 0, 0]}
  link2:
    mass: 1
    inertia: [0.1, 0.1, 0.1]
    position: link1.tip
    rotation: link1.R * rot_z(q2)
    points: {tip: [l, 0, 0]}
points:
  anchor: link2.tip + [0, 1, 0]
particles:
  - {point: link2.tip, mass: 0.5}
springs:
  - {between: [link1.tip, anchor], k: k}
dampers:
  - {between: [link2.tip, anchor], c: 0.1}
forces:
  - {point: link2.tip, force: [F, 0, 0], frame: body}
  - {point: link1.tip, force: [0, F, 0]}
torques:
  - {body: link1, torque: [0, 0, 1]}
  - {body: link2, torque: [0, 0, 1], frame: body}
potential: k*link2.tip.y
constraints:
  reach: link2.tip - [l, l, 0]
outputs:
  angle2: atan2((link2.R*[1, 0, 0]).y, (link2.R*[1, 0, 0]).x)
  axis: transpose(link2.R)*[0, 0, 1]
)";
  const Model m = read_model_string(yaml, "posed.yaml");
  const GiNaC::symbol q1 = m.coordinates[0].q, q2 = m.coordinates[1].q;
  const GiNaC::ex l = m.parameters[0].sym, F = m.parameters[2].sym;
  const Point* tip = m.find_point("link2.tip");
  ASSERT_NE(tip, nullptr);
  auto at = [&](const GiNaC::ex& e) {  // at q1 = 0.3, q2 = 0.7, l = 1
    return GiNaC::ex_to<GiNaC::numeric>(e.subs(GiNaC::lst{q1 == 0.3, q2 == 0.7, l == 1}).evalf())
        .to_double();
  };
  EXPECT_NEAR(at(tip->pos[0]), std::cos(0.3) + std::cos(1.0), 1e-14);
  EXPECT_NEAR(at(tip->pos[1]), std::sin(0.3) + std::sin(1.0), 1e-14);
  ASSERT_EQ(m.forces.size(), 2u);
  // Body frame: F along the link's own x axis, R (F, 0, 0).
  const Mat3 R = m.bodies[1].rotation;
  for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(same(m.forces[0].force[k], R[k][0] * F));
  EXPECT_TRUE(m.torques[1].body_frame);
  EXPECT_FALSE(m.torques[0].body_frame);
  ASSERT_EQ(m.constraints.size(), 2u);  // reach.z is identically zero: dropped (a planar arm)
  EXPECT_EQ(m.constraints[0].name, "reach.x");
  EXPECT_EQ(m.constraints[1].name, "reach.y");
  ASSERT_EQ(m.outputs.size(), 4u);
  EXPECT_EQ(m.outputs[1].name, "axis.x");
  EXPECT_TRUE(same(m.outputs[3].expr, 1));
  EXPECT_TRUE(m.potential.has(q2));
}

// For a free body, vel(body.p) = ṙ + R(ω × p) through Ṙ = RΩ (docs/theory.md §4.4).
TEST(ReaderBodies, VelocityOfAFreeBodyPoint) {
  const Model m = read_model_string(kFree + "outputs:\n  v: vel(brick.corner)\n", "m.yaml");
  const Body& b = m.bodies[0];
  const Vec3 p{m.parameters[1].sym / 2, m.parameters[2].sym / 2, m.parameters[3].sym / 2};
  const Vec3 wxp{b.w[1] * p[2] - b.w[2] * p[1], b.w[2] * p[0] - b.w[0] * p[2],
                 b.w[0] * p[1] - b.w[1] * p[0]};
  const Mat3 R = b.rot();
  for (size_t k = 0; k < 3; ++k)
    EXPECT_TRUE(
        same(m.outputs[k].expr, b.rd[k] + R[k][0] * wxp[0] + R[k][1] * wxp[1] + R[k][2] * wxp[2]))
        << m.outputs[k].expr;
}

struct BadBody {
  const char* label;
  std::string yaml;
  const char* where;
  const char* fragment;
};

const std::string kBody = "bodies:\n  b:\n    mass: 1\n";
const std::string kFreeBody = kBody + "    inertia: [1, 1, 1]\n    frame: free\n    initial: {}\n";

// A body's state columns as the CSV and the bounds name them (b.x … b.z, b.R11 … b.R33) are the
// components of b.r and the entries of b.R in expressions too.
TEST(ReaderBodies, StateColumnNamesAreTheirComponents) {
  const Model m = read_model_string(kFreeBody +
                                        "outputs:\n  height: b.z - b.r.z\n  across: b.x*b.y\n"
                                        "  entry: b.R31 - (b.R*[1, 0, 0]).z\n  top: b.R12\n",
                                    "m.yaml");
  ASSERT_EQ(m.outputs.size(), 4u);
  EXPECT_TRUE(m.outputs[0].expr.is_zero()) << m.outputs[0].expr;
  EXPECT_TRUE((m.outputs[1].expr - m.bodies[0].origin()[0] * m.bodies[0].origin()[1]).is_zero());
  EXPECT_TRUE(GiNaC::expand(m.outputs[2].expr).is_zero()) << m.outputs[2].expr;
  EXPECT_TRUE((m.outputs[3].expr - m.bodies[0].rot()[0][1]).is_zero());
}

// `coordinates: {}` reads as an absent key: the free body's model, nothing else; and with
// neither coordinates nor bodies, the model is refused as when the key is absent.
TEST(ReaderBodies, EmptyCoordinatesMapIsAnAbsentKey) {
  const Model m = read_model_string("coordinates: {}\n" + kFreeBody, "m.yaml");
  EXPECT_TRUE(m.coordinates.empty());
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_TRUE(m.bodies[0].free);
  try {
    read_model_string("coordinates: {}\nparameters: {k: 1}\n", "m.yaml");
    ADD_FAILURE() << "a model without coordinates was read";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("expected a 'coordinates' key"), std::string::npos)
        << e.what();
  }
}

std::vector<BadBody> bad_bodies() {
  return {
      {"unknown key", kBody + "    inertia: [1, 1, 1]\n    frme: free\n", "5:5",
       "unknown key 'frme' in body 'b'"},
      {"non-physical inertia names the body",
       kBody + "    inertia: [1, 1, 3]\n    frame: free\n    initial: {}\n", "2:3",
       "body 'b': non-physical inertia"},
      {"negative moment", kBody + "    inertia: [-1, 1, 1]\n    frame: free\n    initial: {}\n",
       "2:3", "principal moments"},
      {"singular inertia of a free body",
       kBody + "    inertia: [0, 1, 1]\n    frame: free\n    initial: {}\n", "2:3",
       "a free body needs a positive-definite inertia"},
      {"planar form on a body that tilts",
       "coordinates: {q: {initial: 0}}\n" + kBody +
           "    inertia: [0, 0, 1]\n    rotation: rot_x(q)*rot_z(q)\n",
       "3:3", "violate the triangle inequality"},
      {"negative mass", "bodies:\n  b:\n    mass: -1\n    inertia: [1, 1, 1]\n", "3:11",
       "positive mass for body 'b'"},
      {"inertia and shape", kBody + "    inertia: [1, 1, 1]\n    shape: {sphere: {radius: 1}}\n",
       "5:12", "either 'inertia' or 'shape'"},
      {"no inertia", kBody + "    frame: free\n", "3:5", "got none"},
      {"inertia of 2", kBody + "    inertia: [1, 1]\n", "4:14", "got 2"},
      {"two shapes", kBody + "    shape: {box: [1, 1, 1], sphere: {radius: 1}}\n", "4:12",
       "expected one of box, cylinder, sphere"},
      {"unknown shape", kBody + "    shape: {cone: [1, 1]}\n", "4:13", "unknown key 'cone'"},
      {"box of 2", kBody + "    shape: {box: [1, 1]}\n", "4:18", "edge lengths [a, b, c]"},
      {"cylinder without length", kBody + "    shape: {cylinder: {radius: 1}}\n", "4:23",
       "expected 'length' in the cylinder of body 'b'"},
      {"negative radius", kBody + "    shape: {sphere: {radius: -1}}\n", "4:30",
       "positive sphere radius"},
      {"missing initial", kBody + "    inertia: [1, 1, 1]\n    frame: free\n", "2:3",
       "expected 'initial: {position, orientation, velocity, omega}'"},
      {"frame not free", kBody + "    inertia: [1, 1, 1]\n    frame: fixed\n", "5:12",
       "expected 'free' for the frame of body 'b'"},
      {"neither free nor posed", kBody + "    inertia: [1, 1, 1]\n", "2:3", "got neither"},
      {"free and posed", kFreeBody + "    position: [0, 0, 0]\n", "7:15", "got both"},
      {"not a rotation",
       kBody + "    inertia: [1, 1, 1]\n    frame: free\n    initial: "
               "{orientation: {matrix: [[1, 0, 0], [0, 1, 0], [0, 0.1, 1]]}}\n",
       "6:37", "expected a rotation matrix"},
      {"reflection",
       kBody + "    inertia: [1, 1, 1]\n    frame: free\n    initial: "
               "{orientation: {matrix: [[-1, 0, 0], [0, 1, 0], [0, 0, 1]]}}\n",
       "6:37", "det R = -1"},
      {"two orientations",
       kBody + "    inertia: [1, 1, 1]\n    frame: free\n    initial: "
               "{orientation: {euler: [0, 0, 0], quaternion: [1, 0, 0, 0]}}\n",
       "6:28", "expected one of matrix, axis_angle, euler, quaternion"},
      {"short quaternion",
       kBody + "    inertia: [1, 1, 1]\n    frame: free\n    initial: "
               "{orientation: {quaternion: [1, 0, 0]}}\n",
       "6:41", "quaternion [w, x, y, z] for body 'b', got 3 numbers"},
      {"zero axis",
       kBody + "    inertia: [1, 1, 1]\n    frame: free\n    initial: "
               "{orientation: {axis_angle: {axis: [0, 0, 0], angle: 1}}}\n",
       "6:48", "non-zero rotation axis"},
      {"unknown member", kFreeBody + "outputs:\n  o: b.foo.x\n", "8:6",
       "expected r, R, x, y, z, R11 … R33 or a point of body 'b' after '.', got 'foo' (points: "
       "none)"},
      {"bare body", kFreeBody + "outputs:\n  o: b\n", "8:6", "expected b.r, b.R or a point"},
      {"point named R", kFreeBody + "    points: {R: [0, 0, 0]}\n", "7:14",
       "point name other than r and R"},
      {"unknown body in torque", kFreeBody + "torques:\n  - {body: c, torque: [0, 0, 1]}\n", "8:12",
       "expected a body name for a torque, got 'c' (bodies: b)"},
      {"torque frame", kFreeBody + "torques:\n  - {body: b, torque: [0, 0, 1], frame: x}\n", "8:41",
       "'world' or 'body'"},
      {"body-frame force at a plain point",
       kFreeBody +
           "points: {p: [0, 0, 0]}\nforces:\n  - {point: p, force: [1, 0, 0], frame: body}\n",
       "9:41", "expected a body point (body.point) for a body-frame force"},
      {"later body",
       "coordinates: {x: {initial: 0}}\n" + kBody +
           "    inertia: [1, 1, 1]\n    position: c.r\n"
           "  c:\n    mass: 1\n    inertia: [1, 1, 1]\n    rotation: rot_x(x)\n",
       "6:15", "expected a body defined before use"},
      {"matrix for a scalar", "coordinates: {x: {initial: 0}}\nkinetic: rot_z(x)\n", "2:10",
       "expected a scalar for kinetic, got a matrix"},
      {"vector for a rotation",
       "coordinates: {x: {initial: 0}}\n" + kBody +
           "    inertia: [1, 1, 1]\n    rotation: [x, 0, 0]\n",
       "6:16", "expected a vector [x, y, z] for row 1 of rotation of body 'b', got a scalar"},
      {"pose in an initial value", kFreeBody + "coordinates: {x: {initial: b.r.x}}\n", "7:28",
       "got 'b.r' (a body's pose)"},
      {"body point before its body",
       "coordinates: {x: {initial: 0}}\n" + kBody +
           "    inertia: [1, 1, 1]\n    position: c.tip\n"
           "  c:\n    mass: 1\n    inertia: [1, 1, 1]\n    rotation: rot_x(x)\n"
           "    points: {tip: [1, 0, 0]}\n",
       "6:15", "expected a body defined before use"},
  };
}

class ReaderBodyErrors : public ::testing::TestWithParam<BadBody> {};

TEST_P(ReaderBodyErrors, Located) {
  const BadBody& c = GetParam();
  try {
    read_model_string(c.yaml, "bad.yaml");
    FAIL() << c.label << ": no error";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().str(), std::string("bad.yaml:") + c.where) << c.label << ": " << e.what();
    EXPECT_NE(e.detail().find(c.fragment), std::string::npos) << c.label << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Bodies, ReaderBodyErrors, ::testing::ValuesIn(bad_bodies()),
                         [](const auto& info) {
                           std::string s = info.param.label;
                           for (char& ch : s)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return s;
                         });

}  // namespace
}  // namespace lagrange
