// SPDX-License-Identifier: GPL-2.0-or-later
// icgp._icgp.servo: servo scenarios and closed-loop runs, with per-step callbacks and a
// control law written in Python (wrapped by the icgp.servo module).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <limits>
#include <optional>

#include "bindings.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/scenario_profile.h"
#include "icgp/servo/servo_batch.h"
#include "icgp/servo/servo_report.h"
#include "icgp/servo/servo_run.h"
#include "icgp/visp/conversions.h"
#include "numpy_conversions.h"
#include "servo_names.h"

namespace icgp::python {
namespace {

namespace py = pybind11;
using servo::ControlLawKind;
using servo::RobotKind;
using servo::Scenario;
using servo::TrackerKind;

constexpr double kMm = 1e3;                    // metres -> millimetres
constexpr double kDeg = 1.0 / servo::kDegree;  // radians -> degrees

std::string repr_text(const py::handle& object) { return py::repr(object).cast<std::string>(); }

// The names scenario files give robots, laws and trackers.
std::string servo_name(RobotKind robot) { return servo::name_of(robot, servo::robot_names()); }
std::string servo_name(ControlLawKind law) { return servo::name_of(law, servo::control_law_names()); }
std::string servo_name(TrackerKind tracker) { return servo::name_of(tracker, servo::tracker_names()); }
std::string servo_name(servo::Profile profile) { return servo::name_of(profile, servo::profile_names()); }

/// An integer argument in [0, max], or nullopt for None. bool is refused: True is no seed.
std::optional<long long> integer_or_none(const py::object& value, const char* argument, long long max, const char* none) {
  if (value.is_none()) return std::nullopt;
  if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) {
    const py::int_ number = value;
    if (number >= py::int_(0) && number <= py::int_(max)) return number.cast<long long>();
  }
  throw py::value_error(std::string(argument) + ": expected an integer in [0, " + std::to_string(max) + "] or None (" +
                        none + "), got " + repr_text(value));
}

/// A callback argument: None or something callable.
std::optional<py::function> callback(const py::object& value, const char* argument) {
  if (value.is_none()) return std::nullopt;
  if (!PyCallable_Check(value.ptr()))
    throw py::type_error(std::string(argument) + ": expected a callable or None, got " + repr_text(value));
  return value.cast<py::function>();
}

py::array_t<double> matrix_of(const vpHomogeneousMatrix& aMb) { return matrix(to_pose(aMb)); }

py::array_t<double> vector_of(const vpColVector& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  for (unsigned i = 0; i < v.size(); ++i) out.mutable_at(i) = v[i];
  return out;
}

py::dict step_dict(const servo::ServoStep& s) {
  py::dict d;
  d["time"] = s.time;
  d["wMc_true"] = matrix_of(s.wMc_true);
  d["cMo_true"] = matrix_of(s.cMo_true);
  d["cMo_estimated"] = matrix_of(s.cMo_estimated);
  d["servo_t_mm"] = s.servo_t * kMm;
  d["servo_r_deg"] = s.servo_r * kDeg;
  d["track_t_mm"] = s.track_t * kMm;
  d["track_r_deg"] = s.track_r * kDeg;
  d["velocity"] = vector_of(s.velocity);
  d["servo_error_norm"] = s.servo_error_norm;
  d["lost"] = s.lost;
  d["safety_stop"] = s.safety_stop;
  d["dropped"] = s.dropped;
  d["render_ms"] = s.render_ms;
  d["track_ms"] = s.track_ms;
  d["control_ms"] = s.control_ms;
  d["skipped"] = s.skipped;
  d["command_delay_ms"] = s.command_delay * 1e3;
  return d;
}

py::dict summary_dict(const servo::ServoResult& r, const servo::StopSpec& stop, std::optional<long long> trial,
                      py::list steps) {
  const auto or_none = [](bool defined, double value) -> py::object {
    return defined ? py::object(py::float_(value)) : py::object(py::none());
  };
  py::dict d;
  d["scenario"] = r.scenario;
  d["tracker"] = r.tracker;
  d["seed"] = r.seed;
  d["trial"] = trial ? py::object(py::int_(*trial)) : py::object(py::none());
  d["succeeded"] = servo::succeeded(r, stop);
  d["converged"] = r.converged;
  d["converged_step"] = r.converged ? py::object(py::int_(r.converged_step)) : py::object(py::none());
  d["converged_time"] = or_none(r.converged, r.converged_time);
  d["final_t_mm"] = r.final_t * kMm;
  d["final_r_deg"] = r.final_r * kDeg;
  d["mean_track_t_mm"] = r.mean_track_t * kMm;
  d["max_track_t_mm"] = r.max_track_t * kMm;
  d["mean_track_r_deg"] = r.mean_track_r * kDeg;
  d["max_track_r_deg"] = r.max_track_r * kDeg;
  d["max_vouched_track_t_mm"] = r.max_vouched_track_t * kMm;
  d["max_vouched_track_r_deg"] = r.max_vouched_track_r * kDeg;
  d["median_track_ms"] = r.median_track_ms;
  d["steps_per_s"] = r.steps_per_s;
  d["safety_stops"] = r.safety_stops;
  d["recovered"] = r.recovered;
  d["lost_reason"] = r.lost_reason;
  d["joint_limit_stops"] = r.joint_limit_stops;
  d["interrupted"] = r.interrupted;
  d["steps"] = std::move(steps);
  return d;
}

/// What a Python control law returned, as the velocity for the C++ loop, which checks its size.
vpColVector velocity_from(const py::handle& returned) {
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(returned);
  if (!array || array.ndim() != 1)
    throw py::type_error("control: expected a sequence of numbers (the velocity), got " + repr_text(returned));
  vpColVector velocity(static_cast<unsigned>(array.shape(0)));
  for (unsigned i = 0; i < velocity.size(); ++i) velocity[i] = array.at(i);
  return velocity;
}

py::dict state_dict(const servo::ControlState& state) {
  py::dict d;
  d["time"] = state.time;
  d["pose"] = matrix_of(state.pose);
  d["desired"] = matrix_of(state.desired);
  d["robot"] = servo_name(state.robot);
  d["velocity_size"] = state.velocity_size;
  py::array_t<double> jacobian({state.jacobian.getRows(), state.jacobian.getCols()});
  for (unsigned r = 0; r < state.jacobian.getRows(); ++r)
    for (unsigned c = 0; c < state.jacobian.getCols(); ++c) jacobian.mutable_at(r, c) = state.jacobian[r][c];
  d["jacobian"] = jacobian;
  return d;
}

py::dict run(const Scenario& scenario, const py::object& tracker, const py::object& seed_arg,
             const py::object& trial_arg, const py::object& on_step_arg, const py::object& control_arg, bool progress) {
  Scenario s = scenario;
  if (const std::optional<TrackerKind> kind = tracker_kind(tracker)) s.tracker.kind = *kind;
  if (const auto seed = integer_or_none(seed_arg, "seed", std::numeric_limits<unsigned>::max(), "the scenario's"))
    s.seed = static_cast<unsigned>(*seed);
  const std::optional<long long> trial =
      integer_or_none(trial_arg, "trial", std::numeric_limits<int>::max(), "the scenario's own start");
  const std::optional<py::function> on_step = callback(on_step_arg, "on_step");
  const std::optional<py::function> control = callback(control_arg, "control");

  servo::ServoRunOptions options;
  options.progress = progress;
  options.seed = s.seed;
  // The GIL is held only here, around Python code. Every step polls Python's signals, so
  // Ctrl-C raises KeyboardInterrupt at the next step, with callbacks or without.
  py::list steps;
  options.on_step = [&](const servo::RgbdCapture&, const servo::ServoStep& step) {
    py::gil_scoped_acquire gil;
    py::dict d = step_dict(step);
    steps.append(d);
    if (on_step) (*on_step)(d);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  };
  if (control)
    options.control_law = [&](const servo::ControlState& state) {
      py::gil_scoped_acquire gil;
      return velocity_from((*control)(state_dict(state)));
    };
  servo::ServoResult result;
  {
    py::gil_scoped_release release;
    // Trial i of a batch is run_trial's (`icgp servo --trials`): its start and noise seed.
    result = trial ? servo::run_trial(s, s.tracker.kind, static_cast<int>(*trial), options) : servo::run_servo(s, options);
  }
  return summary_dict(result, s.stop, trial, std::move(steps));
}

py::dict stop_dict(const servo::StopSpec& stop) {
  py::dict d;
  d["translation_mm"] = stop.converged_translation * kMm;
  d["rotation_deg"] = stop.converged_rotation * kDeg;
  d["settle_time"] = stop.settle_time;
  d["max_time"] = stop.max_time;
  return d;
}

py::dict trials_dict(const servo::TrialSpec& trials) {
  py::dict d;
  d["translation_mm"] = trials.translation * kMm;
  d["rotation_deg"] = trials.rotation * kDeg;
  return d;
}

py::object optional_matrix(const std::optional<Pose>& pose) {
  return pose ? py::object(matrix(*pose)) : py::object(py::none());
}

constexpr const char* kRunDoc = R"doc(Runs a scenario's closed loop (render -> track -> control -> move) to convergence
or to its time limit, as `icgp servo` does, and returns its summary.

scenario  a Scenario (load_scenario).
tracker   None (the scenario's), "icgp", "visp" or "oracle" (the true pose), as --tracker.
seed      None (the scenario's), or the seed of the sensor noise and of the trials' starts,
          as --seed (there 0 means the scenario's; here 0 is a seed).
trial     None: start at the scenario's start. i: trial i of a batch, as `icgp servo --trials`
          runs it: the start moved by perturbed_start(scenario's trial spread, seed, i) and
          the noise seeded with seed + i, so its numbers are the command's trial i.
on_step   called after every step with the step's dict (below), from the running thread.
control   a control law in place of the scenario's vpServo law: control(state) -> velocity,
          called at every step where the tracker did not report lost (a lost tracker stops
          the robot, without calling it). state is a dict:
            time           seconds of simulated time at the step's capture
            pose           4x4 estimated servoed pose: cMo (object in camera frame), or in a
                           grasp gMo (object in gripper frame), metres
            desired        4x4 where `pose` must go (the scenario's desired_cMo / desired_gMo)
            robot          the scenario's robot: 'free_flying', 'viper850_eye_in_hand', ...
            velocity_size  how many values to return: 6
            jacobian       6 x velocity_size: the twist (v, w) the returned velocity gives the
                           frame the law drives: identity for 'free_flying'; for a Viper 850
                           cVe.eJe (eye-in-hand: the camera's twist), gVe.eJe (grasp: the
                           gripper's) or cVf.fVe.eJe (eye-to-hand: the end effector's, in
                           the camera frame). A law that computes a twist returns
                           pinv(jacobian) @ twist.
          It returns a sequence of floats (a list, a NumPy array): for 'free_flying' the
          camera twist (vx, vy, vz, wx, wy, wz) in the current camera frame, m/s and rad/s;
          for the Viper 850 robots the joint velocities q1'..q6', rad/s. The robot saturates
          it as it does vpServo's output (one factor keeping the direction; arm joints stop
          at their limits); steps' servo_error_norm is NaN (no features s).
progress  a progress line on stderr (not for a trial, which runs as in a batch: quietly).

Returns a dict: scenario, tracker, seed (the noise seed used), trial, succeeded (converged
and the true final error within the thresholds), converged, converged_step and
converged_time (seconds; None when it did not converge), final_t_mm and final_r_deg (true
pose to the desired one at the end), mean/max_track_t_mm and mean/max_track_r_deg (tracker
error over the run), max_vouched_track_t_mm / max_vouched_track_r_deg (the largest on frames
the tracker took and did not report lost), median_track_ms, steps_per_s, safety_stops, recovered, lost_reason
(lost at the end: the tracker's last reason, such as why the object was never found;
empty otherwise), joint_limit_stops, interrupted, and steps: one dict per step with time, wMc_true
(4x4, where the camera truly was in the world: log.csv's camera pose), cMo_true and
cMo_estimated (4x4), servo_t_mm / servo_r_deg (true servoed pose to the desired one),
track_t_mm / track_r_deg (estimated to true), velocity (the one the robot follows at the
end of the step), servo_error_norm, lost, safety_stop, dropped, render_ms, track_ms,
control_ms, skipped (the tracker was busy: timing real) and command_delay_ms (from the
frame's exposure to its command's arrival; NaN for a skipped frame).

An exception raised in on_step or control ends the run and is raised from run() as it was
(Ctrl-C too: KeyboardInterrupt at the next step). Bad arguments raise ValueError or
TypeError naming them; a run the scenario cannot make raises icgp.Error with the message of
`icgp servo`.

    s = icgp.servo.load_scenario("scenarios/default.yaml")
    r = icgp.servo.run(s, "oracle", on_step=lambda step: print(step["time"], step["servo_t_mm"]))
    print(r["succeeded"], r["final_t_mm"], r["final_r_deg"])
)doc";

/// Fields set over a scenario file's, as a dict {key path: value} in their order.
py::dict overrides_dict(const std::vector<servo::FieldValue>& overrides) {
  py::dict d;
  for (const servo::FieldValue& o : overrides) d[py::str(o.field)] = o.value;
  return d;
}

std::vector<servo::FieldValue> overrides_of(const py::dict& d) {
  std::vector<servo::FieldValue> overrides;
  for (const auto& [field, value] : d) overrides.push_back({field.cast<std::string>(), value.cast<double>()});
  return overrides;
}

}  // namespace

void register_servo(py::module_& m) {
  py::module_ servo = m.def_submodule("servo", "The servo simulator's C++ side (use icgp.servo)");
  py::class_<Scenario>(servo, "Scenario",
                       "A servo scenario read from its YAML file (icgp.servo.load_scenario; docs/servo.md has the "
                       "format). Read-only but for `seed`; poses are 4x4 NumPy arrays, metres.")
      .def_readonly("name", &Scenario::name)
      .def_readonly("description", &Scenario::description)
      .def_readonly("file", &Scenario::file, "The YAML file it was read from.")
      .def_readwrite("seed", &Scenario::seed, "Seed of the sensor noise and of the trials' random starts.")
      .def_property_readonly("robot", [](const Scenario& s) { return servo_name(s.robot); },
                             "What the control law moves: 'free_flying', 'viper850_eye_in_hand', "
                             "'viper850_eye_to_hand' or 'viper850_grasp'.")
      .def_property_readonly("law", [](const Scenario& s) { return servo_name(s.control.law); },
                             "The scenario's control law: 'pbvs' or 'ibvs'.")
      .def_property_readonly("tracker", [](const Scenario& s) { return servo_name(s.tracker.kind); },
                             "The tracker in the loop: 'icgp', 'visp', 'oracle' or 'image_oracle'.")
      .def_property_readonly("profile", [](const Scenario& s) { return servo_name(s.profile); },
                             "The cell the file's fields were read over: 'realistic' or 'ideal'.")
      .def_property_readonly("rate_hz", [](const Scenario& s) { return s.camera.rate_hz; },
                             "Frames per second of the camera: one step of the loop per frame.")
      .def_property_readonly("image_size", [](const Scenario& s) {
             return py::make_tuple(s.camera.color.width, s.camera.color.height);
           }, "(width, height) of the colour image, pixels.")
      .def_property_readonly("initial_cMo", [](const Scenario& s) { return matrix(s.initial_cMo); },
                             "The object in the camera frame at the start.")
      .def_property_readonly("desired_cMo", [](const Scenario& s) {
             return s.grasp ? py::object(py::none()) : py::object(matrix(s.desired_cMo));
           }, "Where the control law brings cMo; None in a grasp (it servoes desired_gMo).")
      .def_property_readonly("start_gMo", [](const Scenario& s) {
             return optional_matrix(s.grasp ? std::optional<Pose>(s.grasp->start_gMo) : std::nullopt);
           }, "A grasp's object in the gripper frame at the start; None for other robots.")
      .def_property_readonly("desired_gMo", [](const Scenario& s) {
             return optional_matrix(s.grasp ? std::optional<Pose>(s.grasp->desired_gMo) : std::nullopt);
           }, "A grasp's pre-grasp pose, where the control law brings gMo; None for other robots.")
      .def_property_readonly("stop", [](const Scenario& s) { return stop_dict(s.stop); },
                             "When a run ends and succeeds: {'translation_mm', 'rotation_deg', 'settle_time', "
                             "'max_time'} (seconds), the keys of the file's stop:.")
      .def_property_readonly("trials", [](const Scenario& s) { return trials_dict(s.trials); },
                             "The largest random move of a trial's start: {'translation_mm', 'rotation_deg'}.")
      .def("__repr__", [](const Scenario& s) {
        return "<icgp.servo.Scenario '" + s.name + "' " + servo_name(s.robot) + " " + servo_name(s.control.law) + " " +
               servo_name(s.tracker.kind) + " seed " + std::to_string(s.seed) + " from " + s.file + ">";
      })
      // Sent to other processes (Dask workers) as its file, made absolute here since a
      // worker may run in another folder, and its seed; read again there: the file and the
      // models it names must be readable where the trial runs.
      .def_property_readonly("overrides", [](const Scenario& s) { return overrides_dict(s.overrides); },
                             "The fields load_scenario set over the file's: {'camera.latency_ms': 66.7, ...}.")
      // Sent to other processes (Dask workers) as its file, made absolute here since a
      // worker may run in another folder, its fields set over the file's and its seed; read
      // again there: the file and the models it names must be readable where the trial runs.
      .def(py::pickle(
          [](const Scenario& s) {
            return py::make_tuple(std::filesystem::absolute(s.file).string(), s.seed, overrides_dict(s.overrides));
          },
          [](const py::tuple& state) {
            Scenario s = servo::load_scenario(state[0].cast<std::string>(), models_dir(),
                                              overrides_of(state[2].cast<py::dict>()));
            s.seed = state[1].cast<unsigned>();
            return s;
          }));
  servo.def(
      "load_scenario",
      [](const std::filesystem::path& path, const py::dict& overrides) {
        return servo::load_scenario(path.string(), models_dir(), overrides_of(overrides));
      },
      py::arg("path"), py::arg("overrides") = py::dict(),
      "Reads a scenario file (YAML, docs/servo.md); models are named against icgp.models_dir(). `overrides` sets\n"
      "numeric fields over the file's by their key paths, {'camera.latency_ms': 66.7}, read as the file's own\n"
      "values are (icgp servo --sweep). A file that cannot be used raises icgp.Error naming the file and the key,\n"
      "as `icgp servo` says it.");
  servo.def("run", &run, py::arg("scenario"), py::arg("tracker") = py::none(), py::kw_only(),
            py::arg("seed") = py::none(), py::arg("trial") = py::none(), py::arg("on_step") = py::none(),
            py::arg("control") = py::none(), py::arg("progress") = false, kRunDoc);
}

}  // namespace icgp::python
