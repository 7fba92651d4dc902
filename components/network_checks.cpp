#include "components/network_checks.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <numeric>

#include "core/nearest_name.hpp"

namespace shudder::components {

void check_judged_on(const NetworkSpec& spec) {
  for (const auto& c : spec.clutches) {
    if (c.judged_on.empty()) continue;
    std::vector<std::string> shafts;
    for (const auto& s : spec.shafts) shafts.push_back(s.name);
    if (std::find(shafts.begin(), shafts.end(), c.judged_on) != shafts.end()) continue;
    const std::string near = nearest_key(c.judged_on, shafts);
    std::string list;
    for (const auto& n : shafts) list += (list.empty() ? "" : ", ") + n;
    throw NetworkError(c.name, "judged_on = '" + c.judged_on + "' is no shaft of the network" +
                                   (near.empty() ? "" : "; did you mean '" + near + "'?") +
                                   (list.empty() ? " (it has no shaft)" : " (shafts: " + list + ")"));
  }
}

void check_massless_nodes(const NetworkSpec& spec, const Topology& topology) {
  const auto& fixed_nodes = topology.fixed_nodes;
  for (std::size_t i = 0; i < spec.inertias.size(); ++i)
    if (spec.inertias[i].inertia_kg_m2 == 0.0 && !fixed_nodes.count(static_cast<int>(i)))
      throw NetworkError(spec.inertias[i].name,
                         "has no inertia and nothing fixes its speed (no gear, differential or speed source on it); "
                         "give it inertia_kg_m2 > 0");
}

void check_constraints(const NetworkSpec& spec, const BuiltNetwork& out) {
  const auto& net = out.network;
  const int n = static_cast<int>(out.node_names.size());
  Eigen::MatrixXd g(0, n);
  const auto add_row = [&](const std::string& who, const Eigen::RowVectorXd& row, bool prescribes) {
    Eigen::MatrixXd h(g.rows() + 1, n);
    h << g, row;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(h);
    lu.setThreshold(1e-10);
    if (lu.rank() <= g.rows())
      throw NetworkError(who,
                         "over-constrains the network: the speeds it ties are already fixed by the gears, "
                         "differentials and speed sources before it (a closed loop of gears); remove it or "
                         "replace one gear of the loop by a shaft or a clutch");
    // Gears and differentials alone must leave every node free to turn: a loop whose ratios
    // disagree admits only standstill (a tie-up).
    if (!prescribes) {
      const Eigen::MatrixXd free = lu.kernel();
      for (int i = 0; i < n; ++i)
        if (lu.dimensionOfKernel() == 0 || free.row(i).norm() < 1e-9)
          throw NetworkError(who, "closes a loop of gears whose ratios disagree, which locks '" + out.node_names[i] +
                                      "' at standstill; make the ratios around the loop agree, or replace one gear by "
                                      "a shaft or a clutch");
    }
    g = h;
  };
  for (const auto& gr : net.gears()) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    r[gr.a] += 1.0;
    r[gr.b] -= gr.ratio;
    add_row(gr.name, r, false);
  }
  for (const auto& d : net.differentials()) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    r[d.left] += 1.0;
    r[d.right] += 1.0;
    r[d.carrier] -= 2.0;
    add_row(d.name, r, false);
  }
  for (const auto& s : net.speed_sources()) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    r[s.node] = 1.0;
    add_row(s.name, r, true);
  }
  // The mass left on the free motions must be positive definite (a massless node between gears
  // only, e.g., still needs mass somewhere on its side).
  const Eigen::MatrixXd basis = net.constraint_basis({});
  if (basis.cols() > 0) {
    const Eigen::MatrixXd m = basis.transpose() * net.mass_matrix() * basis;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(m);
    if (es.eigenvalues().minCoeff() <= 1e-12 * std::max(1.0, es.eigenvalues().maxCoeff())) {
      std::string massless;
      for (const auto& i : spec.inertias)
        if (i.inertia_kg_m2 == 0.0) massless += (massless.empty() ? "" : ", ") + i.name;
      throw NetworkError(massless.empty() ? "" : spec.inertias.front().name,
                         "a part of the network has no inertia (massless nodes: " + massless +
                             "); give one of its nodes inertia_kg_m2 > 0");
    }
  }
}

void check_connected(const BuiltNetwork& out, const Topology& topology) {
  const auto& links = topology.links;
  const auto& driven_nodes = topology.driven_nodes;
  const int n = static_cast<int>(out.node_names.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& [a, bb] : links)
    if (a >= 0 && bb >= 0) parent[find(a)] = find(bb);
  std::vector<bool> alive(static_cast<std::size_t>(n), false);
  for (int i = 0; i < n; ++i)
    if (driven_nodes.count(i) || out.initial_speed_rad_s[i] != 0.0) alive[find(i)] = true;
  for (int i = 0; i < n; ++i)
    if (!alive[find(i)]) {
      std::vector<std::string> part;
      for (int j = 0; j < n; ++j)
        if (find(j) == find(i)) part.push_back(out.node_names[j]);
      std::string list;
      for (const auto& p : part) list += (list.empty() ? "" : ", ") + p;
      throw NetworkError(out.node_names[i], "its part of the network (" + list +
                                                ") starts at rest and nothing drives it (no source, motor, engine or "
                                                "speed source, and no link to one); connect it or give it a speed");
    }
}

}  // namespace shudder::components
