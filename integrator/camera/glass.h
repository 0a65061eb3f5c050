// Glass: the refractive index n(λ) of one medium of a lens prescription (lens_file.h).
//
// | model    | from                         | n(λ) |
// |----------|------------------------------|------|
// | air      | N = 1                        | 1 at every λ |
// | constant | N alone (no glass, no abbe)  | n_d at every λ: no dispersion (pbrt-v4's files) |
// | abbe     | N = n_d and abbe = V_d       | two-term Cauchy n = A + B/λ², with A, B such that n(λ_d) = n_d and n(λ_F) − n(λ_C) = (n_d − 1)/V_d exactly |
// | table    | N = n_d and glass = NAME     | n_d + t(λ) − t(λ_d): the catalogue table t (luts/spectra/glasses/NAME.csv, eta against nm) through a natural cubic spline, shifted so that n(λ_d) = n_d |
//
// λ_d = 587.56 nm (helium d), λ_F = 486.13 nm (hydrogen F), λ_C = 656.27 nm (hydrogen C):
// the lines of the Abbe number V_d = (n_d − 1)/(n_F − n_C).
//
// The table is shifted rather than taken as is so that a published prescription keeps its
// focal length at λ_d when a glass is named only for its dispersion (pbrt-v4's files give
// indices such as 1.67 that are no catalogue glass); with the glass's own n_d on the line
// the shift is the table's rounding (BK7: 3·10⁻⁶). Outside the table's wavelengths n holds
// its end value (as the dielectric material's Extrapolation::kClamp); a natural cubic spline
// through Schott's tabulated BK7 (22 nm steps) gives V_d = 64.18 against Sellmeier's 64.14,
// where linear interpolation gives 64.00.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace camsim {

inline constexpr double kLambdaDNm = 587.5618;  // helium d line, nm
inline constexpr double kLambdaFNm = 486.1327;  // hydrogen F line, nm
inline constexpr double kLambdaCNm = 656.2725;  // hydrogen C line, nm

enum class GlassModel { kAir, kConstant, kAbbe, kTable };

class Glass {
 public:
  Glass() = default;  // air
  static Glass air() { return {}; }
  static Glass constant(double nd);
  static Glass abbe(double nd, double abbeNumber);
  // A catalogue table (λ strictly increasing, nm; eta > 0) shifted to n(λ_d) = nd. name is
  // the catalogue name, for reports. At least two rows.
  static Glass table(std::string name, std::vector<double> lambdaNm, std::vector<double> eta,
                     double nd);

  // n at λ (nm).
  double index(double lambdaNm) const;
  bool disperses() const { return model_ == GlassModel::kAbbe || model_ == GlassModel::kTable; }
  GlassModel model() const { return model_; }
  double nd() const { return nd_; }                  // n at λ_d
  double abbeNumber() const;                         // V_d; +∞ without dispersion
  const std::string& name() const { return name_; }  // the catalogue name, or ""

 private:
  // The natural cubic spline through (x, y): second derivatives m at the knots.
  struct Spline {
    std::vector<double> x, y, m;
    double operator()(double at) const;
  };

  GlassModel model_ = GlassModel::kAir;
  double nd_ = 1.0;
  double cauchyA_ = 1.0, cauchyB_ = 0.0;  // n = A + B/λ², B in nm²
  double shift_ = 0.0;                    // table: nd − t(λ_d)
  std::string name_;
  std::shared_ptr<const Spline> spline_;  // table only; shared by copies
};

}  // namespace camsim
