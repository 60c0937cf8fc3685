// Python classes of the policy interface: what a policy observes (NumPy arrays for points), the actions it returns,
// how actions ended, its per-episode context and its random stream. They are the C++ structs themselves.

#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay::python {

namespace {

using namespace freeplay::policies;
using PolygonRows = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

std::string point_text(const Vec2& p) { return fmt::format("({:.3f}, {:.3f})", p.x(), p.y()); }

void bind_observation(py::module_& m) {
  py::class_<Pose2>(m, "Pose2", "A planar pose in `sandtray`: x, y (m) and theta (rad).")
      .def(py::init([](double x, double y, double theta) { return Pose2{x, y, theta}; }), py::arg("x") = 0.0,
           py::arg("y") = 0.0, py::arg("theta") = 0.0)
      .def_readonly("x", &Pose2::x)
      .def_readonly("y", &Pose2::y)
      .def_readonly("theta", &Pose2::theta)
      .def_property_readonly("position", [](const Pose2& p) { return Vec2(p.position()); })
      .def("__repr__", [](const Pose2& p) { return fmt::format("Pose2(x={:.3f}, y={:.3f}, theta={:.3f})", p.x, p.y, p.theta); });
  py::class_<ItemObservation>(m, "ItemObservation", "An item as the robot sees it on /tf and in the touch frames.")
      .def_readonly("name", &ItemObservation::name)
      .def_readonly("pose", &ItemObservation::pose)
      .def_property_readonly("position", [](const ItemObservation& i) { return Vec2(i.pose.position()); })
      .def_readonly("touched_by_child", &ItemObservation::touched_by_child)
      .def_readonly("held_by_robot", &ItemObservation::held_by_robot)
      .def_readonly("visible", &ItemObservation::visible)
      .def("__repr__", [](const ItemObservation& i) { return fmt::format("ItemObservation({}, {})", i.name, point_text(i.pose.position())); });
  py::class_<ZoneObservation>(m, "ZoneObservation", "A colour zone from /zones.")
      .def_readonly("colour", &ZoneObservation::colour)
      .def_property_readonly("polygon", [](const ZoneObservation& z) {
        PolygonRows rows(static_cast<Eigen::Index>(z.polygon.size()), 2);
        for (std::size_t i = 0; i < z.polygon.size(); ++i) rows.row(static_cast<Eigen::Index>(i)) = z.polygon[i].transpose();
        return rows;
      }, "vertices as an (n, 2) array, last vertex not repeated")
      .def_readonly("centroid", &ZoneObservation::centroid);
  py::class_<TouchObservation>(m, "TouchObservation", "An active finger on the screen.")
      .def_readonly("finger", &TouchObservation::finger)
      .def_readonly("position", &TouchObservation::position);
  py::enum_<PerceivedGaze>(m, "PerceivedGaze", "Where a perceived child seems to look.")
      .value("Unknown", PerceivedGaze::Unknown)
      .value("Robot", PerceivedGaze::Robot)
      .value("Partner", PerceivedGaze::Partner)
      .value("Screen", PerceivedGaze::Screen)
      .value("Away", PerceivedGaze::Away);
  py::class_<PerceivedChild>(m, "PerceivedChild", "A child as the robot's perception reports it (noisy, late).")
      .def_readonly("seat", &PerceivedChild::seat)
      .def_readonly("face_detected", &PerceivedChild::face_detected)
      .def_readonly("gaze", &PerceivedChild::gaze)
      .def_readonly("gaze_on_screen", &PerceivedChild::gaze_on_screen)
      .def_readonly("speaking", &PerceivedChild::speaking)
      .def_readonly("addressing_robot", &PerceivedChild::addressing_robot)
      .def_readonly("seconds_since_touch", &PerceivedChild::seconds_since_touch)
      .def_readonly("moving_item", &PerceivedChild::moving_item);
  py::class_<RobotSelf>(m, "RobotSelf", "The robot's own state.")
      .def_readonly("moving_item", &RobotSelf::moving_item)
      .def_readonly("current_item", &RobotSelf::current_item)
      .def_readonly("speaking", &RobotSelf::speaking)
      .def_readonly("arm_reach_centre", &RobotSelf::arm_reach_centre)
      .def_readonly("arm_reach_radius", &RobotSelf::arm_reach_radius)
      .def_readonly("arm_reach_known", &RobotSelf::arm_reach_known);
  py::class_<Observation>(m, "Observation", "Everything a policy may observe at one 10 Hz decision.")
      .def_readonly("t", &Observation::t)
      .def_readonly("items", &Observation::items)
      .def_readonly("zones", &Observation::zones)
      .def_readonly("touches", &Observation::touches)
      .def_readonly("interaction_events", &Observation::interaction_events)
      .def_readonly("children", &Observation::children)
      .def_readonly("self", &Observation::self)
      .def("item", [](const Observation& o, const std::string& name) -> std::optional<ItemObservation> {
        if (const auto* i = o.item(name)) return *i;
        return std::nullopt;
      }, py::arg("name"), "The observation of item `name`, or None.")
      .def("__repr__", [](const Observation& o) {
        return fmt::format("Observation(t={:.1f}, {} items, {} touches, {} children)", o.t, o.items.size(), o.touches.size(), o.children.size());
      });
}

void bind_actions(py::module_& m) {
  py::class_<MoveItem>(m, "MoveItem", "Start a move_sandbox_items goal: drag `item` to `target` (m, sandtray).")
      .def(py::init([](std::string item, Vec2 target) { return MoveItem{std::move(item), target}; }), py::arg("item"), py::arg("target"))
      .def_readwrite("item", &MoveItem::item)
      .def_readwrite("target", &MoveItem::target)
      .def("__repr__", [](const MoveItem& a) { return fmt::format("MoveItem('{}', {})", a.item, point_text(a.target)); });
  py::class_<LookAt>(m, "LookAt", "Look at a 3-D point in sandtray or at a child's face ('purple'/'yellow').")
      .def(py::init([](std::optional<Eigen::Vector3d> point, std::optional<std::string> child) {
             if (point.has_value() == child.has_value()) {
               throw InputError("LookAt needs exactly one of point and child", "LookAt", "point=(x, y, z) or child='purple'|'yellow'");
             }
             return LookAt{point, std::move(child)};
           }), py::arg("point") = std::nullopt, py::arg("child") = std::nullopt)
      .def_readwrite("point", &LookAt::point)
      .def_readwrite("child", &LookAt::child)
      .def("__repr__", [](const LookAt& a) {
        return a.child ? fmt::format("LookAt(child='{}')", *a.child)
                       : fmt::format("LookAt(point=({:.3f}, {:.3f}, {:.3f}))", a.point->x(), a.point->y(), a.point->z());
      });
  py::class_<PointAt>(m, "PointAt", "Point at a screen point (m, sandtray) with the right arm.")
      .def(py::init([](Vec2 point) { return PointAt{point}; }), py::arg("point"))
      .def_readwrite("point", &PointAt::point)
      .def("__repr__", [](const PointAt& a) { return fmt::format("PointAt({})", point_text(a.point)); });
  py::class_<Say>(m, "Say", "Say something to 'purple', 'yellow' or both ('').")
      .def(py::init([](std::string text, std::string addressee) { return Say{std::move(text), std::move(addressee)}; }),
           py::arg("text"), py::arg("addressee") = "")
      .def_readwrite("text", &Say::text)
      .def_readwrite("addressee", &Say::addressee)
      .def("__repr__", [](const Say& a) { return fmt::format("Say('{}', addressee='{}')", a.text, a.addressee); });
  py::class_<Wait>(m, "Wait", "Do nothing new for `seconds`.")
      .def(py::init([](double seconds) { return Wait{seconds}; }), py::arg("seconds"))
      .def_readwrite("seconds", &Wait::seconds)
      .def("__repr__", [](const Wait& a) { return fmt::format("Wait({})", a.seconds); });
  py::class_<CancelMove>(m, "CancelMove", "Cancel the running move.")
      .def(py::init<>())
      .def("__repr__", [](const CancelMove&) { return std::string("CancelMove()"); });

  py::class_<ActionResult> result(m, "ActionResult", "How a move or an utterance ended.");
  py::enum_<ActionResult::Kind>(result, "Kind")
      .value("MoveSucceeded", ActionResult::Kind::MoveSucceeded)
      .value("MoveFailed", ActionResult::Kind::MoveFailed)
      .value("MoveCancelled", ActionResult::Kind::MoveCancelled)
      .value("SpeechFinished", ActionResult::Kind::SpeechFinished);
  result.def_readonly("kind", &ActionResult::kind)
      .def_readonly("item", &ActionResult::item)
      .def_readonly("reason", &ActionResult::reason);
  py::class_<PolicyContext>(m, "PolicyContext", "What a policy is told once per episode.")
      .def_readonly("robot_seat", &PolicyContext::robot_seat)
      .def_readonly("item_names", &PolicyContext::item_names);
}

void bind_rng(py::module_& m) {
  py::class_<Rng>(m, "Rng", "The policy's own random stream (xoshiro256**): use it, not `random`, for determinism.")
      .def(py::init<std::uint64_t>(), py::arg("seed") = 0)
      .def("next_u64", [](Rng& r) { return r(); }, "next raw 64-bit draw")
      .def("uniform", py::overload_cast<double, double>(&Rng::uniform), py::arg("lo") = 0.0, py::arg("hi") = 1.0)
      .def("uniform_int", &Rng::uniform_int, py::arg("lo"), py::arg("hi"), "integer in [lo, hi]")
      .def("normal", &Rng::normal, py::arg("mean") = 0.0, py::arg("sd") = 1.0)
      .def("exponential", &Rng::exponential, py::arg("rate"))
      .def("bernoulli", &Rng::bernoulli, py::arg("p"))
      .def("shuffle", [](Rng& r, py::list items) {
        std::vector<py::object> shuffled;
        for (const auto item : items) shuffled.push_back(py::reinterpret_borrow<py::object>(item));
        r.shuffle(shuffled);
        for (std::size_t i = 0; i < shuffled.size(); ++i) items[i] = shuffled[i];
      }, py::arg("items"), "Fisher–Yates shuffle of a list in place (the draws of the C++ Rng::shuffle)");
}

void bind_geometry(py::module_& m) {
  m.def("point_in_polygon", &point_in_polygon, py::arg("polygon"), py::arg("point"),
        "True when `point` lies in `polygon` ((n, 2) array or list of points): core's test, as C++ policies use it");
}

template <class A>
bool append_if(const py::handle& item, std::vector<Action>& out) {
  if (!py::isinstance<A>(item)) return false;
  out.emplace_back(item.cast<A>());
  return true;
}

bool append_action(const py::handle& item, std::vector<Action>& out) {
  return append_if<MoveItem>(item, out) || append_if<LookAt>(item, out) || append_if<PointAt>(item, out) ||
         append_if<Say>(item, out) || append_if<Wait>(item, out) || append_if<CancelMove>(item, out);
}

}  // namespace

std::vector<Action> actions_from_python(const py::handle& returned, const std::string& policy) {
  std::vector<Action> actions;
  if (PyList_CheckExact(returned.ptr()) && PyList_GET_SIZE(returned.ptr()) == 0) return actions;  // the common "no action"
  if (returned.is_none() || append_action(returned, actions)) return actions;
  const auto bad = [&](const py::handle& what) {
    return InputError(fmt::format("policy '{}' returned {} from decide(), which is not an action", policy,
                                  py::repr(what).cast<std::string>()),
                      "decide", "a list of freeplay.MoveItem, LookAt, PointAt, Say, Wait, CancelMove (or None)");
  };
  if (!py::isinstance<py::sequence>(returned) || py::isinstance<py::str>(returned)) throw bad(returned);
  for (const auto item : returned) {
    if (!append_action(item, actions)) throw bad(item);
  }
  return actions;
}

void bind_types(py::module_& m) {
  bind_observation(m);
  bind_actions(m);
  bind_rng(m);
  bind_geometry(m);
}

}  // namespace freeplay::python
