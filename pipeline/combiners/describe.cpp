#include "pipeline/combiners/describe.h"

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string_view>

namespace ffsim::combiners {

namespace {

// Concatenation by appends (GCC 12's -Wrestrict misfires on chains of operator+).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (std::string_view p : parts) s.append(p);
  return s;
}

// A term: a constant (exact multiple of 1/4 here) or an expression text.
struct Term {
  bool constant = false;
  double value = 0;
  std::string text;
  bool atom = true;  // needs no parentheses as a factor
};

std::string fmt(double v) {
  if (v == std::floor(v)) return std::to_string(static_cast<long>(v));
  const double q = v * 4;
  char buf[32];
  if (q == std::floor(q)) {
    const long n = static_cast<long>(q);
    if (n % 2 == 0) std::snprintf(buf, sizeof buf, "%ld/2", n / 2);
    else std::snprintf(buf, sizeof buf, "%ld/4", n);
  } else {
    std::snprintf(buf, sizeof buf, "%g", v);
  }
  return buf;
}

Term konst(double v) { return {true, v, fmt(v), v >= 0 && v == std::floor(v)}; }
Term expr(std::string t, bool atom) { return {false, 0, std::move(t), atom}; }
std::string paren(const Term& t) { return t.atom ? t.text : cat({"(", t.text, ")"}); }

Term mul(const Term& a, const Term& b) {
  if (a.constant && b.constant) return konst(a.value * b.value);
  if ((a.constant && a.value == 0) || (b.constant && b.value == 0)) return konst(0);
  if (a.constant && a.value == 1) return b;
  if (b.constant && b.value == 1) return a;
  if (a.constant && a.value == -1) return expr(cat({"-", paren(b)}), false);
  if (b.constant && b.value == -1) return expr(cat({"-", paren(a)}), false);
  return expr(cat({paren(a), " * ", paren(b)}), false);
}

Term add(const Term& a, const Term& b) {
  if (a.constant && b.constant) return konst(a.value + b.value);
  if (a.constant && a.value == 0) return b;
  if (b.constant && b.value == 0) return a;
  if (!b.text.empty() && b.text[0] == '-') return expr(cat({a.text, " - ", std::string_view(b.text).substr(1)}), false);
  return expr(cat({a.text, " + ", b.text}), false);
}

Term dot(const Term& a, const Term& b) {
  if ((a.constant && a.value == 0) || (b.constant && b.value == 0)) return konst(0);
  return expr(cat({"dot(", a.text, ", ", b.text, ")"}), true);
}

std::string swizzle(const PlannedVar& v) {
  if (v.comp[0] == 3) return ".a";
  if (v.comp[0] == 2 && v.comp[1] == 2) return ".b";
  return ".rgb";
}

double map_zero(Mapping m) {
  switch (m) {
    case Mapping::UnsignedInvert: return 1;
    case Mapping::ExpandNormal: return -1;
    case Mapping::ExpandNegate: return 1;
    case Mapping::HalfBiasNormal: return -0.5;
    case Mapping::HalfBiasNegate: return 0.5;
    default: return 0;
  }
}

Term mapped(Mapping m, const std::string& x, bool non_negative) {
  switch (m) {
    case Mapping::UnsignedIdentity: return non_negative ? expr(x, true) : expr(cat({"max(", x, ", 0)"}), true);
    case Mapping::UnsignedInvert: return expr(cat({"(1 - ", x, ")"}), true);
    case Mapping::ExpandNormal: return expr(cat({"expand(", x, ")"}), true);
    case Mapping::ExpandNegate: return expr(cat({"-expand(", x, ")"}), false);
    case Mapping::HalfBiasNormal: return expr(cat({"(", x, " - 1/2)"}), true);
    case Mapping::HalfBiasNegate: return expr(cat({"(1/2 - ", x, ")"}), true);
    case Mapping::SignedIdentity: return expr(x, true);
    case Mapping::SignedNegate: return expr(cat({"-", x}), false);
  }
  return expr(x, true);
}

Term var_term(const PlannedVar& v, const bool (&written)[kRegisterCount]) {
  if (v.reg == kZero) return konst(map_zero(v.mapping));
  return mapped(v.mapping, cat({register_short_name(v.reg), swizzle(v)}), !written[v.reg]);
}

void line(std::string& out, const std::string& label, bool& first, const std::string& text) {
  char pad[24];
  std::snprintf(pad, sizeof pad, "%-15s", first ? label.c_str() : "");
  out.append(pad).append(text).append("\n");
  first = false;
}

}  // namespace

std::string describe(const CombinerPlan& plan) {
  std::string out;
  bool written[kRegisterCount] = {};
  for (const PlannedStage& st : plan.stages) {
    bool wrote[kRegisterCount] = {};
    for (int portion = 0; portion < 2; ++portion) {
      const PlannedPortion& p = portion == 0 ? st.rgb : st.alpha;
      if (!p.run) continue;
      const std::string label = cat({"stage ", std::to_string(st.index), portion == 0 ? " rgb:" : " alpha:"});
      Term v[4];
      for (std::size_t i = 0; i < 4; ++i) v[i] = var_term(p.var[i], written);
      const Term ab = p.ab_dot ? dot(v[0], v[1]) : mul(v[0], v[1]);
      const Term cd = p.cd_dot ? dot(v[2], v[3]) : mul(v[2], v[3]);
      const Term sum = p.mux ? expr(cat({"spare0.a >= 1/2 ? ", cd.text, " : ", ab.text}), false) : add(ab, cd);
      bool first = true;
      for (std::size_t o = 0; o < 3; ++o) {
        const int d = p.dest[o];
        if (d < 0) continue;
        wrote[d] = true;
        Term x = o == 0 ? ab : o == 1 ? cd : sum;
        if (p.bias) x = add(x, konst(-0.5));
        if (p.scale2 == 1) x = x.constant ? konst(x.value / 2) : expr(cat({paren(x), " / 2"}), false);
        else if (p.scale2 != 2) x = mul(x, konst(p.scale2 / 2));
        line(out, label, first, cat({register_short_name(d), portion == 0 ? ".rgb = " : ".a = ", x.text}));
      }
    }
    for (int r = 0; r < kRegisterCount; ++r) written[r] = written[r] || wrote[r];
  }
  const PlannedFinal& f = plan.final;
  auto final_term = [&](std::size_t i) -> Term {
    const PlannedVar& v = f.var[i];
    if (v.reg == kETimesF) {
      const Term ef = mul(var_term(f.var[4], written), var_term(f.var[5], written));
      return ef.constant ? konst(v.mapping == Mapping::UnsignedInvert ? 1 - ef.value : ef.value)
                         : mapped(v.mapping, paren(ef), true);
    }
    if (v.reg == kSpare0PlusSecondary) {
      const std::string s0 = written[kSpare0] ? "max(spare0.rgb, 0)" : "spare0.rgb";
      const std::string sc = written[kSecondaryColor] ? "max(secondary.rgb, 0)" : "secondary.rgb";
      const std::string s = f.color_sum_clamp ? cat({"min(", s0, " + ", sc, ", 1)"}) : cat({"(", s0, " + ", sc, ")"});
      return mapped(v.mapping, s, true);
    }
    return var_term(v, written);
  };
  const Term a = final_term(0), b = final_term(1), c = final_term(2), d = final_term(3);
  const Term one_minus_a = a.constant ? konst(1 - a.value) : expr(cat({"1 - ", a.text}), false);
  Term rgb = add(add(mul(a, b), mul(one_minus_a, c)), d);
  if (!(d.constant && d.value == 0) && !rgb.constant) rgb = expr(cat({"min(", rgb.text, ", 1)"}), true);
  if (rgb.constant) rgb = konst(std::min(rgb.value, 1.0));
  bool first = true;
  line(out, "final:", first, cat({"fcoc.rgb = ", rgb.text}));
  line(out, "final:", first, cat({"fcoc.a = ", var_term(f.var[6], written).text}));
  if (plan.final_may_exceed_two)
    out += "note: the final RGB sum can exceed 2 (COLOR_SUM_CLAMP_NV is FALSE); GeForce 256 computes such values "
           "incorrectly, ffsim computes the ideal value\n";
  return out;
}

}  // namespace ffsim::combiners
