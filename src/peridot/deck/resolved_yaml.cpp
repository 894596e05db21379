// The resolved deck: what the run understood, written next to its results so that a run folder
// describes itself. Every value is explicit and in SI; parse_deck reads it back unchanged.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "peridot/deck/deck.hpp"

namespace peridot {

namespace {

/// Shortest text that reads back to the same double.
std::string number(double v) { return fmt::format("{}", v); }

void emit_point(YAML::Emitter& out, Vec3 v) {
  out << YAML::Flow << YAML::BeginSeq << number(v.x) << number(v.y) << number(v.z) << YAML::EndSeq;
}

void emit_names(YAML::Emitter& out, const std::vector<std::string>& names) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const std::string& n : names) out << n;
  out << YAML::EndSeq;
}

void emit_shape(YAML::Emitter& out, const Shape& s) {
  out << YAML::BeginMap;
  switch (s.kind) {
    case Shape::Kind::box:
      out << YAML::Key << "box" << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "min" << YAML::Value;
      emit_point(out, s.lo);
      out << YAML::Key << "max" << YAML::Value;
      emit_point(out, s.hi);
      out << YAML::EndMap;
      break;
    case Shape::Kind::sphere:
      out << YAML::Key << "sphere" << YAML::Value << YAML::BeginMap << YAML::Key << "center" << YAML::Value;
      emit_point(out, s.center);
      out << YAML::Key << "radius" << YAML::Value << number(s.radius) << YAML::EndMap;
      break;
    case Shape::Kind::cylinder:
    case Shape::Kind::tube: {
      bool tube = s.kind == Shape::Kind::tube;
      out << YAML::Key << (tube ? "tube" : "cylinder") << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "center" << YAML::Value;
      emit_point(out, s.center);
      if (tube) out << YAML::Key << "inner_radius" << YAML::Value << number(s.inner_radius);
      out << YAML::Key << (tube ? "outer_radius" : "radius") << YAML::Value << number(s.radius);
      if (s.length > 0) {  // 3D only: a 2D disc or annulus has neither length nor axis
        out << YAML::Key << "axis" << YAML::Value;
        emit_point(out, s.axis);
        out << YAML::Key << "length" << YAML::Value << number(s.length);
      }
      out << YAML::EndMap;
      break;
    }
    case Shape::Kind::union_of:
    case Shape::Kind::difference:
      out << YAML::Key << (s.kind == Shape::Kind::union_of ? "union" : "difference") << YAML::Value << YAML::BeginSeq;
      for (const Shape& child : s.children) emit_shape(out, child);
      out << YAML::EndSeq;
      break;
  }
  out << YAML::EndMap;
}

void emit_components(YAML::Emitter& out, const std::optional<Expression> (&component)[3]) {
  for (int d = 0; d < 3; ++d)
    if (component[d]) out << YAML::Key << std::string(1, "xyz"[d]) << YAML::Value << component[d]->text;
}

std::string_view influence_name(InfluenceKind k) {
  return k == InfluenceKind::constant ? "constant" : k == InfluenceKind::inverse_distance ? "inverse_distance" : "gaussian";
}

void emit_discretization(YAML::Emitter& out, const Problem& p) {
  out << YAML::Key << "discretization" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "dimension" << YAML::Value << p.dimension;
  if (p.spacing > 0) out << YAML::Key << "spacing" << YAML::Value << number(p.spacing);
  out << YAML::Key << "horizon" << YAML::Value << number(p.horizon);
  if (p.dimension == 2) {
    out << YAML::Key << "plane" << YAML::Value << (p.plane == PlaneKind::stress ? "stress" : "strain");
    out << YAML::Key << "thickness" << YAML::Value << number(p.thickness);
  }
  if (p.dimension == 1) out << YAML::Key << "area" << YAML::Value << number(p.area);
  out << YAML::Key << "lattice_origin" << YAML::Value;
  emit_point(out, p.lattice_origin);
  out << YAML::Key << "jitter" << YAML::Value << number(p.jitter);
  out << YAML::Key << "seed" << YAML::Value << p.seed;
  const char* partial_volume[] = {"none", "extended", "horizon"};
  out << YAML::Key << "partial_volume" << YAML::Value << partial_volume[static_cast<int>(p.partial_volume)];
  out << YAML::Key << "quadrature" << YAML::Value
      << (p.quadrature == QuadratureKind::isotropic ? "isotropic" : "one_point");
  out << YAML::EndMap;
}

void emit_value(YAML::Emitter& out, const Parameters::Entry& e) {
  switch (e.kind) {
    case Parameters::Kind::text: out << e.text; return;
    case Parameters::Kind::integer: out << static_cast<std::int64_t>(e.number); return;
    case Parameters::Kind::boolean: out << (e.number != 0); return;
    case Parameters::Kind::number: out << number(e.number); return;
  }
}

/// A model's or solver's own parameters (in its key table's order), so that the resolved deck runs the same
/// model or solver; "SECTION.KEY" entries go into a nested mapping, "LIST[i].KEY" ones into the i-th mapping
/// of a sequence.
void emit_parameters(YAML::Emitter& out, const Parameters& parameters) {
  std::string open_section, open_list;  // the nested mapping ("SECTION" or "LIST[i]") and sequence open now
  auto close_section = [&] {
    if (!open_section.empty()) out << YAML::EndMap;
    open_section.clear();
  };
  auto close_list = [&] {
    close_section();
    if (!open_list.empty()) out << YAML::EndSeq;
    open_list.clear();
  };
  for (const Parameters::Entry& e : parameters.entries()) {
    const std::size_t dot = e.key.find('.');
    const std::string section = dot == std::string::npos ? "" : e.key.substr(0, dot);
    const std::size_t bracket = section.find('[');
    const std::string list = bracket == std::string::npos ? "" : section.substr(0, bracket);
    if (section != open_section) {
      if (list != open_list) {
        close_list();
        if (!list.empty()) out << YAML::Key << list << YAML::Value << YAML::BeginSeq;
        open_list = list;
      }
      close_section();
      if (!list.empty()) out << YAML::BeginMap;
      else if (!section.empty()) out << YAML::Key << section << YAML::Value << YAML::BeginMap;
      open_section = section;
    }
    out << YAML::Key << (dot == std::string::npos ? e.key : e.key.substr(dot + 1)) << YAML::Value;
    emit_value(out, e);
  }
  close_list();
}

void emit_materials(YAML::Emitter& out, const Problem& p) {
  out << YAML::Key << "materials" << YAML::Value << YAML::BeginMap;
  for (const MaterialSpec& m : p.materials) {
    out << YAML::Key << m.name << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "model" << YAML::Value << m.model;
    out << YAML::Key << "density" << YAML::Value << number(m.density);
    if (p.dimension != 1) {  // a bar is E alone
      out << YAML::Key << "bulk_modulus" << YAML::Value << number(m.elastic.bulk_modulus);
      out << YAML::Key << "shear_modulus" << YAML::Value << number(m.elastic.shear_modulus);
    }
    out << YAML::Key << "youngs_modulus" << YAML::Value << number(m.elastic.youngs_modulus);
    if (p.dimension != 1) out << YAML::Key << "poisson_ratio" << YAML::Value << number(m.elastic.poisson_ratio);
    out << YAML::Key << "influence" << YAML::Value << std::string(influence_name(m.influence));
    emit_parameters(out, m.parameters);
    if (m.damage.enabled) {
      out << YAML::Key << "damage" << YAML::Value << YAML::BeginMap;
      if (m.damage.critical_stretch) out << YAML::Key << "critical_stretch" << YAML::Value << number(*m.damage.critical_stretch);
      if (m.damage.fracture_energy) out << YAML::Key << "fracture_energy" << YAML::Value << number(*m.damage.fracture_energy);
      // stretch, the default, is left out: the resolved decks of stretch runs stay as they were.
      if (m.damage.criterion == DamageCriterion::energy) out << YAML::Key << "criterion" << YAML::Value << "energy";
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void emit_bodies(YAML::Emitter& out, const Problem& p) {
  out << YAML::Key << "bodies" << YAML::Value << YAML::BeginMap;
  for (const BodySpec& b : p.bodies) {
    out << YAML::Key << b.name << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "material" << YAML::Value << b.material;
    if (b.shape) {
      out << YAML::Key << "shape" << YAML::Value;
      emit_shape(out, *b.shape);
    } else if (b.mesh) {
      out << YAML::Key << "mesh" << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "file" << YAML::Value << b.mesh->file;
      out << YAML::Key << "format" << YAML::Value << b.mesh->format;
      if (!b.mesh->block.empty()) out << YAML::Key << "block" << YAML::Value << b.mesh->block;
      out << YAML::Key << "scale" << YAML::Value << number(b.mesh->scale);
      out << YAML::EndMap;
    } else {
      out << YAML::Key << "points_file" << YAML::Value << b.points_file;
    }
    if (b.block_filter) out << YAML::Key << "block" << YAML::Value << *b.block_filter;
    out << YAML::Key << "horizon" << YAML::Value << number(b.horizon);
    if (b.volume_constraint > 0) out << YAML::Key << "volume_constraint" << YAML::Value << number(b.volume_constraint);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

/// `key: [items]` in block style, left out when there are none.
template <class Item, class EmitItem>
void emit_list(YAML::Emitter& out, const char* key, const std::vector<Item>& items, EmitItem emit_item) {
  if (items.empty()) return;
  out << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (const Item& item : items) {
    out << YAML::BeginMap;
    emit_item(item);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void emit_precracks_and_node_sets(YAML::Emitter& out, const Problem& p) {
  emit_list(out, "precracks", p.precracks, [&](const PrecrackSpec& c) {
    if (c.is_point) {
      out << YAML::Key << "at" << YAML::Value << number(c.at);
      return;
    }
    if (c.is_segment) {
      out << YAML::Key << "segment" << YAML::Value << YAML::BeginMap << YAML::Key << "from" << YAML::Value;
      emit_point(out, c.a);
      out << YAML::Key << "to" << YAML::Value;
      emit_point(out, c.b);
    } else {
      out << YAML::Key << "rectangle" << YAML::Value << YAML::BeginMap << YAML::Key << "origin" << YAML::Value;
      emit_point(out, c.origin);
      out << YAML::Key << "edge1" << YAML::Value;
      emit_point(out, c.edge1);
      out << YAML::Key << "edge2" << YAML::Value;
      emit_point(out, c.edge2);
    }
    out << YAML::EndMap;
  });

  if (std::any_of(p.node_sets.begin(), p.node_sets.end(), [](const NodeSetSpec& n) { return !n.generated; })) {
    out << YAML::Key << "node_sets" << YAML::Value << YAML::BeginMap;
    for (const NodeSetSpec& n : p.node_sets) {
      if (n.generated) continue;  // the deck makes it again from its body's volume_constraint
      out << YAML::Key << n.name << YAML::Value << YAML::BeginMap;
      if (n.shape) {
        out << YAML::Key << "shape" << YAML::Value;
        emit_shape(out, *n.shape);
      } else if (!n.mesh_set.empty()) {
        out << YAML::Key << "mesh_set" << YAML::Value << n.mesh_set;
      } else {
        out << YAML::Key << "ids_file" << YAML::Value << n.ids_file;
      }
      if (!n.bodies.empty()) {
        out << YAML::Key << "bodies" << YAML::Value;
        emit_names(out, n.bodies);
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  if (!p.no_fail_sets.empty()) {
    out << YAML::Key << "no_fail" << YAML::Value;
    emit_names(out, p.no_fail_sets);
  }
}

void emit_loads(YAML::Emitter& out, const Problem& p) {
  emit_list(out, "initial_conditions", p.initial_conditions, [&](const InitialConditionSpec& ic) {
    if (!ic.node_set.empty()) out << YAML::Key << "node_set" << YAML::Value << ic.node_set;
    bool displacement = ic.kind == InitialConditionSpec::Kind::displacement;
    out << YAML::Key << (displacement ? "displacement" : "velocity") << YAML::Value << YAML::BeginMap;
    emit_components(out, ic.component);
    out << YAML::EndMap;
  });
  // One entry per component, as the Problem holds them.
  emit_list(out, "boundary_conditions", p.boundary_conditions, [&](const BoundaryConditionSpec& bc) {
    bool displacement = bc.kind == BoundaryConditionSpec::Kind::displacement;
    out << YAML::Key << "node_set" << YAML::Value << bc.node_set;
    out << YAML::Key << (displacement ? "displacement" : "velocity") << YAML::Value << YAML::BeginMap;
    out << YAML::Key << std::string(1, "xyz"[bc.component]) << YAML::Value << bc.value.text;
    out << YAML::EndMap;
  });
  emit_list(out, "body_forces", p.body_forces, [&](const BodyForceSpec& f) {
    if (!f.node_set.empty()) out << YAML::Key << "node_set" << YAML::Value << f.node_set;
    emit_components(out, f.component);
  });
  emit_list(out, "tractions", p.tractions, [&](const TractionSpec& t) {
    out << YAML::Key << "node_set" << YAML::Value << t.node_set;
    out << YAML::Key << "depth" << YAML::Value << number(t.depth);
    emit_components(out, t.component);
  });
  emit_list(out, "rigid_walls", p.rigid_walls, [&](const RigidWallSpec& w) {
    out << YAML::Key << "name" << YAML::Value << w.name;
    out << YAML::Key << "point" << YAML::Value;
    emit_point(out, w.point);
    out << YAML::Key << "normal" << YAML::Value;
    emit_point(out, w.normal);
    out << YAML::Key << "speed" << YAML::Value << number(w.speed);
    out << YAML::Key << "stiffness_factor" << YAML::Value << number(w.stiffness_factor);
    out << YAML::Key << "contact" << YAML::Value << (w.contact == WallContactKind::symmetry ? "symmetry" : "penalty");
  });
}

void emit_contact(YAML::Emitter& out, const Problem& p) {
  emit_list(out, "rigid_bodies", p.rigid_bodies, [&](const RigidBodySpec& b) {
    out << YAML::Key << "name" << YAML::Value << b.name;
    const char* shapes[] = {"sphere", "cylinder", "box", "plane"};
    out << YAML::Key << shapes[static_cast<int>(b.shape)] << YAML::Value << YAML::BeginMap;
    switch (b.shape) {
      case RigidShapeKind::sphere:
      case RigidShapeKind::cylinder:
        out << YAML::Key << "center" << YAML::Value;
        emit_point(out, b.center);
        if (b.shape == RigidShapeKind::cylinder) {
          out << YAML::Key << "axis" << YAML::Value;
          emit_point(out, b.axis);
          out << YAML::Key << "length" << YAML::Value << number(b.length);
        }
        out << YAML::Key << "radius" << YAML::Value << number(b.radius);
        break;
      case RigidShapeKind::box:
        out << YAML::Key << "min" << YAML::Value;
        emit_point(out, b.lo);
        out << YAML::Key << "max" << YAML::Value;
        emit_point(out, b.hi);
        break;
      case RigidShapeKind::plane:
        out << YAML::Key << "point" << YAML::Value;
        emit_point(out, b.center);
        out << YAML::Key << "normal" << YAML::Value;
        emit_point(out, b.axis);
        break;
    }
    out << YAML::EndMap;
    if (b.motion == RigidMotionKind::prescribed) {
      out << YAML::Key << "displacement" << YAML::Value << YAML::BeginMap;
      emit_components(out, b.displacement);
      out << YAML::EndMap;
    } else if (b.motion == RigidMotionKind::free) {
      out << YAML::Key << "mass" << YAML::Value << number(b.mass);
      out << YAML::Key << "velocity" << YAML::Value;
      emit_point(out, b.velocity);
    }
    if (b.indenter_stiffness > 0)
      out << YAML::Key << "indenter_stiffness" << YAML::Value << number(b.indenter_stiffness);
    else
      out << YAML::Key << "stiffness_factor" << YAML::Value << number(b.stiffness_factor);
  });
  if (!p.contact) return;
  const ContactSpec& c = *p.contact;
  out << YAML::Key << "contact" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "stiffness_factor" << YAML::Value << number(c.stiffness_factor);
  out << YAML::Key << "distance_factor" << YAML::Value << number(c.distance_factor);
  out << YAML::Key << "reference_fraction" << YAML::Value << number(c.reference_fraction);
  out << YAML::Key << "skin" << YAML::Value << number(c.skin);
  out << YAML::Key << "barrier_fraction" << YAML::Value << number(c.barrier_fraction);
  emit_list(out, "friction", c.friction, [&](const FrictionSpec& f) {
    out << YAML::Key << "bodies" << YAML::Value << YAML::Flow << YAML::BeginSeq << f.first;
    if (f.second != f.first) out << f.second;
    out << YAML::EndSeq;
    out << YAML::Key << "coefficient" << YAML::Value << number(f.coefficient);
  });
  out << YAML::EndMap;
}

void emit_temperature(YAML::Emitter& out, const Problem& p) {
  if (!p.temperature) return;
  out << YAML::Key << "temperature" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "value" << YAML::Value << p.temperature->value.text;
  out << YAML::Key << "reference" << YAML::Value << number(p.temperature->reference);
  out << YAML::EndMap;
}

void emit_solver_and_output(YAML::Emitter& out, const Problem& p) {
  const char* partition[] = {"rcb", "rib", "hsfc"};
  out << YAML::Key << "decomposition" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "method" << YAML::Value << partition[static_cast<int>(p.partition)];
  out << YAML::EndMap;
  out << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << p.solver.type;
  emit_parameters(out, p.solver.parameters);
  out << YAML::EndMap;

  const OutputSpec& o = p.output;
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "directory" << YAML::Value << o.directory;
  if (o.exodus_every > 0)
    out << YAML::Key << "exodus" << YAML::Value << YAML::BeginMap << YAML::Key << "every" << YAML::Value << o.exodus_every
        << YAML::Key << "file" << YAML::Value << o.exodus_file << YAML::EndMap;
  if (o.history_every > 0) {
    out << YAML::Key << "history" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "every" << YAML::Value << o.history_every;
    out << YAML::Key << "file" << YAML::Value << o.history_file;
    out << YAML::Key << "reaction" << YAML::Value;
    emit_names(out, o.reaction_sets);
    out << YAML::Key << "probes" << YAML::Value << YAML::BeginSeq;
    for (const ProbeSpec& probe : o.probes) {
      out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << probe.name << YAML::Key << "point" << YAML::Value;
      emit_point(out, probe.point);
      out << YAML::Key << "field" << YAML::Value << probe.field << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
  }
  if (o.checkpoints())
    out << YAML::Key << "checkpoint" << YAML::Value << YAML::BeginMap << YAML::Key << "every" << YAML::Value
        << o.checkpoint_every << YAML::Key << "wall_time" << YAML::Value << number(o.checkpoint_wall_time) << YAML::Key
        << "keep" << YAML::Value << o.checkpoint_keep << YAML::EndMap;
  out << YAML::Key << "progress" << YAML::Value << o.progress;
  out << YAML::EndMap;
}

}  // namespace

std::string resolved_deck_yaml(const Problem& p) {
  YAML::Emitter out;
  out.SetBoolFormat(YAML::TrueFalseBool);
  out << YAML::Comment("Resolved from " + p.deck_path + " by peridot: every default filled in, SI units") << YAML::Newline;
  out << YAML::BeginMap;
  emit_discretization(out, p);
  emit_materials(out, p);
  emit_bodies(out, p);
  emit_precracks_and_node_sets(out, p);
  emit_loads(out, p);
  emit_contact(out, p);
  emit_temperature(out, p);
  emit_solver_and_output(out, p);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace peridot
