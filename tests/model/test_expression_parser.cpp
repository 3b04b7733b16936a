// The expression language on its own: precedence, vector algebra, functions, errors with offsets.

#include <gtest/gtest.h>

#include <map>

#include "model/expression_parser.hpp"
#include "support/ginac_values.hpp"

namespace lagrange::model {
namespace {

/// Symbols a, b, c (scalars) and u, w (vectors [a, b, c] and [1, 2, 3]) for the tests below.
struct Names {
  GiNaC::symbol a{"a"}, b{"b"}, c{"c"};
  std::map<std::string, Value> table{{"a", Value::of(a)},
                                     {"b", Value::of(b)},
                                     {"c", Value::of(c)},
                                     {"u", Value::of(Vec3{a, b, c})},
                                     {"w", Value::of(Vec3{1, 2, 3})}};

  Value parse(const std::string& text) const {
    ParseContext ctx;
    ctx.resolve = [this](const std::string& n, size_t) -> std::optional<Value> {
      auto it = table.find(n);
      return it == table.end() ? std::nullopt : std::optional<Value>(it->second);
    };
    return parse_expression(text, ctx);
  }
  GiNaC::ex scalar(const std::string& text) const {
    Value v = parse(text);
    EXPECT_FALSE(v.is_vector) << text;
    return v.scalar;
  }
  Vec3 vec(const std::string& text) const {
    Value v = parse(text);
    EXPECT_TRUE(v.is_vector) << text;
    return v.vec;
  }
};

/// The ExprError thrown for `text`, or a failure.
ExprError error_of(const Names& n, const std::string& text) {
  try {
    n.parse(text);
  } catch (const ExprError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for " << text;
  return ExprError{0, ""};
}

// An expression that must fail, the byte offset the error points at, and a message fragment.
struct Case {
  const char* text;
  size_t offset;
  const char* fragment;
};

template <size_t N>
void expect_errors(const Names& n, const Case (&cases)[N]) {
  for (const Case& c : cases) {
    ExprError e = error_of(n, c.text);
    EXPECT_EQ(e.offset, c.offset) << c.text << ": " << e.message;
    EXPECT_NE(e.message.find(c.fragment), std::string::npos) << c.text << ": " << e.message;
  }
}

TEST(ExpressionParser, NumbersAreExact) {
  Names n;
  EXPECT_EQ(n.scalar("2.5"), GiNaC::numeric(5, 2));
  EXPECT_EQ(n.scalar("1e-3"), GiNaC::numeric(1, 1000));
  EXPECT_EQ(n.scalar(".5"), GiNaC::numeric(1, 2));
  EXPECT_EQ(n.scalar("12E2"), GiNaC::numeric(1200));
}

TEST(ExpressionParser, Precedence) {
  Names n;
  const auto &a = n.a, &b = n.b, &c = n.c;
  EXPECT_TRUE(same(n.scalar("a + b*c"), a + b * c));
  EXPECT_TRUE(same(n.scalar("(a + b)*c"), (a + b) * c));
  EXPECT_TRUE(same(n.scalar("a - b - c"), a - b - c));
  EXPECT_TRUE(same(n.scalar("a / b / c"), a / b / c));
  EXPECT_TRUE(same(n.scalar("a / b * c"), a * c / b));
  EXPECT_TRUE(same(n.scalar("-a^2"), -pow(a, 2)));
  EXPECT_TRUE(same(n.scalar("a^b^c"), pow(a, pow(b, c))));
  EXPECT_TRUE(same(n.scalar("2^-1"), GiNaC::numeric(1, 2)));
  EXPECT_TRUE(same(n.scalar("a*-b"), -a * b));
  EXPECT_TRUE(same(n.scalar("--a"), a));
  EXPECT_TRUE(same(n.scalar("2*a^2/4"), pow(a, 2) / 2));
  EXPECT_TRUE(same(n.scalar("pi"), GiNaC::Pi));
}

TEST(ExpressionParser, Functions) {
  Names n;
  const auto& a = n.a;
  EXPECT_TRUE(same(n.scalar("sin(a)^2 + cos(a)^2"), pow(sin(a), 2) + pow(cos(a), 2)));
  EXPECT_TRUE(same(n.scalar("atan2(a, 2)"), GiNaC::atan2(a, 2)));
  EXPECT_TRUE(same(n.scalar("sqrt(a)"), GiNaC::sqrt(a)));
  EXPECT_TRUE(same(n.scalar("abs(a)"), GiNaC::abs(a)));
  EXPECT_TRUE(same(n.scalar("exp(log(a))"), a));
  EXPECT_TRUE(same(n.scalar("tanh(a) + sinh(a) + cosh(a) + asin(a) + acos(a) + atan(a) + tan(a)"),
                   tanh(a) + sinh(a) + cosh(a) + asin(a) + acos(a) + atan(a) + tan(a)));
}

TEST(ExpressionParser, VectorAlgebra) {
  Names n;
  const auto &a = n.a, &b = n.b, &c = n.c;
  Vec3 s = n.vec("u + 2*w - w/2");
  EXPECT_TRUE(same(s[0], a + GiNaC::numeric(3, 2)));
  EXPECT_TRUE(same(s[1], b + 3));
  EXPECT_TRUE(same(s[2], c + GiNaC::numeric(9, 2)));
  Vec3 m = n.vec("-[a, 1, 0]*b");
  EXPECT_TRUE(same(m[0], -a * b));
  EXPECT_TRUE(same(m[1], -b));
  EXPECT_TRUE(same(n.scalar("dot(u, w)"), a + 2 * b + 3 * c));
  Vec3 x = n.vec("cross(u, w)");
  EXPECT_TRUE(same(x[0], 3 * b - 2 * c));
  EXPECT_TRUE(same(x[1], c - 3 * a));
  EXPECT_TRUE(same(x[2], 2 * a - b));
  EXPECT_TRUE(same(n.scalar("norm(w)"), GiNaC::sqrt(GiNaC::ex(14))));
  EXPECT_TRUE(same(n.scalar("u.x + u.y*10 + w.z"), a + 10 * b + 3));
  EXPECT_TRUE(same(n.scalar("(u + w).y"), b + 2));
  EXPECT_TRUE(same(n.scalar("[a, b, c].z^2"), pow(c, 2)));
  EXPECT_TRUE(same(n.scalar("cross([1,0,0], [0,1,0]).z"), 1));
}

TEST(ExpressionParser, ErrorsCarryOffsets) {
  Names n;
  const Case cases[] = {
      {"a + foo", 4, "unknown name 'foo'"},
      {"bar(a)", 0, "unknown function 'bar'"},
      {"[1, 2]", 0, "3 components, got 2"},
      {"a + u", 2, "a scalar + a vector"},
      {"u * w", 2, "two vectors"},
      {"a / u", 2, "scalar divisor"},
      {"a.x", 1, "expected a vector before '.x'"},
      {"u.w", 2, "expected x, y or z"},
      {"sin(u)", 0, "expected a scalar as argument 1 of 'sin'"},
      {"dot(u)", 0, "expected 2 arguments for 'dot', got 1"},
      {"norm(a)", 0, "expected a vector as argument 1 of 'norm'"},
      {"(a + b", 6, "expected ')'"},
      {"a b", 2, "expected an operator or the end"},
      {"a $ b", 2, "got '$'"},
      {"1e999", 0, "finite number"},
      {"a / 0", 2, "division by zero"},
      {"sin", 3, "expected '(' after function 'sin'"},
      {"", 0, "expected a number, a name"},
      {"u^2", 1, "scalar ^ scalar"},
      {"[[1,2,3], 0, 0]", 0, "got a vector as component 1"},
  };
  expect_errors(n, cases);
}

// 3×3 matrices: literals of three rows, rot_x/y/z, products, transpose (docs/theory.md §4.4).
TEST(ExpressionParser, Matrices) {
  Names n;
  auto mat = [&](const std::string& text) {
    Value v = n.parse(text);
    EXPECT_TRUE(v.is_matrix) << text;
    return v.mat;
  };
  const Mat3 Rz = mat("rot_z(a)");
  EXPECT_TRUE(same(Rz[0][1], -sin(n.a)));
  EXPECT_TRUE(same(Rz[1][0], sin(n.a)));
  EXPECT_TRUE(same(Rz[2][2], 1));
  const Mat3 Rx = mat("rot_x(a)");
  EXPECT_TRUE(same(Rx[1][2], -sin(n.a)));
  const Mat3 Ry = mat("rot_y(a)");
  EXPECT_TRUE(same(Ry[0][2], sin(n.a)));  // x' = cos a x + sin a z
  EXPECT_TRUE(same(Ry[2][0], -sin(n.a)));
  const Mat3 I = mat("transpose(rot_z(a)) * rot_z(a)");
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      EXPECT_TRUE(
          same((I[i][j] - (i == j ? 1 : 0)).subs(pow(sin(n.a), 2) == 1 - pow(cos(n.a), 2)), 0));
  const Mat3 L = mat("[[1, 2, 3], [0, b, 0], u]");
  EXPECT_TRUE(same(L[1][1], n.b));
  EXPECT_TRUE(same(L[2][0], n.a));
  const Vec3 Lw = n.vec("[[1, 2, 3], [0, b, 0], u] * w");
  EXPECT_TRUE(same(Lw[0], 14));
  EXPECT_TRUE(same(Lw[1], 2 * n.b));
  EXPECT_TRUE(same(Lw[2], n.a + 2 * n.b + 3 * n.c));
  const Mat3 S = mat("2*rot_z(0) - rot_z(0)/2 + -rot_z(0)");
  EXPECT_TRUE(same(S[0][0], GiNaC::numeric(1, 2)));
  EXPECT_TRUE(same(n.vec("rot_z(pi/2)*[1, 0, 0]")[1], 1));
}

TEST(ExpressionParser, MatrixTypeErrors) {
  Names n;
  const Case cases[] = {
      {"u * rot_z(a)", 2, "got a vector * a matrix"},
      {"rot_z(a) + u", 9, "a matrix + a vector"},
      {"rot_z(a) + 1", 9, "a matrix + a scalar"},
      {"rot_z(a).x", 8, "expected a vector before '.x', got a matrix"},
      {"rot_z(a)^2", 8, "scalar ^ scalar"},
      {"dot(rot_z(a), u)", 0, "expected a vector as argument 1 of 'dot', got a matrix"},
      {"sin(rot_z(a))", 0, "expected a scalar as argument 1 of 'sin', got a matrix"},
      {"rot_z(u)", 0, "expected a scalar as argument 1 of 'rot_z'"},
      {"transpose(u)", 0, "expected a matrix as argument 1 of 'transpose', got a vector"},
      {"u / rot_z(a)", 2, "scalar divisor"},
      {"[rot_z(a), u, u]", 0, "got a matrix as component 1"},
  };
  expect_errors(n, cases);
}

TEST(ExpressionParser, DeepNestingIsAnErrorNotACrash) {
  Names n;
  std::string deep = std::string(100000, '(') + "a" + std::string(100000, ')');
  EXPECT_NE(error_of(n, deep).message.find("at most 500 levels"), std::string::npos);
  EXPECT_NE(error_of(n, std::string(100000, '-') + "a").message.find("500"), std::string::npos);
  std::string tower;
  for (int i = 0; i < 100000; ++i) tower += "a^";
  EXPECT_NE(error_of(n, tower + "a").message.find("500"), std::string::npos);
  std::string ok = std::string(400, '(') + "a" + std::string(400, ')');
  EXPECT_TRUE(same(n.scalar(ok), n.a));
}

TEST(ExpressionParser, ReferencedNamesSkipFunctionsAndComponents) {
  auto refs = referenced_names("p1 + [sin(q), p2.x, 0]");
  ASSERT_EQ(refs.size(), 3u);
  EXPECT_EQ(refs[0], std::make_pair(std::string("p1"), size_t{0}));
  EXPECT_EQ(refs[1], std::make_pair(std::string("q"), size_t{10}));
  EXPECT_EQ(refs[2], std::make_pair(std::string("p2"), size_t{14}));
  EXPECT_TRUE(is_builtin_function("cross"));
  EXPECT_FALSE(is_builtin_function("theta"));
}

}  // namespace
}  // namespace lagrange::model
