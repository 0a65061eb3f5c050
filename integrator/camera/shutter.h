// Shutter: when, and how much, each row of the sensor is exposed.
//
// | parameter       | unit | default  | meaning |
// |-----------------|------|----------|---------|
// | open            | s    | 0        | start of the exposure of row 0 |
// | close           | s    | 1/60     | end of the exposure of row 0 |
// | ramp_open       | s    | 0        | trapezoid: efficiency rises linearly 0 → 1 over this time |
// | ramp_close      | s    | 0        | trapezoid: efficiency falls 1 → 0 over this time |
// | curve           | s, — | —        | instead of the trapezoid: tabulated (t, s(t)), piecewise linear |
// | type            | —    | global   | global: every row as row 0; rolling: row j is delayed by j·row_time |
// | row_time        | s    | 0        | rolling shutter: readout delay between consecutive rows |
//
// Rows are read from the top of the image (row 0) to the bottom. The exposure of row j is
//   Q_j = ∫ s(t − j·t_row) E(t) dt,      T_eff = ∫ s(t) dt  (the effective exposure time)
// and time samples are drawn with density s(t)/T_eff, so each sample carries weight T_eff.
#pragma once

#include <vector>

#include "sensor/base/enum_names.h"

namespace camsim {

class Shutter {
 public:
  enum class Type { kGlobal, kRolling };

  // Efficiency s(t) through the points (t_i, s_i), t strictly increasing, s ≥ 0, 0 outside.
  Shutter(std::vector<double> times, std::vector<double> efficiency, Type type, double rowTime);
  static Shutter box(double open, double close);
  static Shutter trapezoid(double open, double close, double rampOpen, double rampClose,
                           Type type = Type::kGlobal, double rowTime = 0.0);

  // The same curve stretched in time by k about the opening time (exposure × k).
  // InputError (key "shutter") when its times would no longer be apart in double precision.
  Shutter scaled(double k) const;
  // The same curve moved later by dt seconds (a frame of a sequence); the same error.
  Shutter shifted(double dt) const;

  double open() const { return times_.front(); }
  double close() const { return times_.back(); }
  // The frame's reference time (s): the middle of open → close; poses in the dataset
  // metadata and the motion field's frame times are taken here.
  double centre() const { return 0.5 * (open() + close()); }
  double effectiveTime() const { return total_; }  // T_eff, s
  Type type() const { return type_; }
  double rowTime() const { return type_ == Type::kRolling ? rowTime_ : 0.0; }
  double efficiency(double t) const;  // s(t) for row 0
  // The curve's points (t_i, s_i), as built (the sidecar writes them back as a scene's).
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& values() const { return values_; }

  // A time for row 0 drawn with density s(t)/T_eff from u in [0,1).
  double sample(double u) const;
  // Delay of a row's exposure window (0 for a global shutter).
  double rowOffset(int row) const { return type_ == Type::kRolling ? row * rowTime_ : 0.0; }

 private:
  std::vector<double> times_, values_, cdf_;  // cdf_[i] = ∫ s from t_0 to t_i
  double total_ = 0.0;
  Type type_;
  double rowTime_;
};
// The scene's `camera.shutter.type` names (sensor/base/enum_names.h).
template <>
struct EnumNames<Shutter::Type> {
  static constexpr EnumName<Shutter::Type> kTable[] = {{Shutter::Type::kGlobal, "global"},
                                                       {Shutter::Type::kRolling, "rolling"}};
};

}  // namespace camsim
