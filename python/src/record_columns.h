// record_columns.h — internal to python/src: many PairResult records as columns (numpy arrays
// and lists of Fractions), the one conversion that solve_batch and mesh_contacts share.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common.h"

namespace pdd_python {

constexpr int kLabelChars = 8;  // the longest label, "EE:a:b:+"

// n records as columns, keyed as definitions §6 (pair_result.h's kValueKeys / kLabelKeys):
//   intersecting                (n,) bool
//   the values of `values`      bit k of `values` selects kValueKeys[k] (the bits of
//                               pdd::mesh::Variant); fast: (n,) float64, exact: a list of n
//                               fractions.Fraction
//   their labels                (n,) numpy str arrays ('<U8'), "" for no label
//   q1_A, q1_B (if `positions`) fast: (n, 4, 3) float64; exact: n nested lists of Fractions
//   definitions §9 (if `global`)       pdd2_global, pdd2_global_normal, q1_A_global, q1_B_global:
//                               fast (n,), (n, 3) (NaN where no normal), (n, 4, 3) float64;
//                               exact lists of n Fractions, [x, y, z] Fractions or None,
//                               nested lists of Fractions, and pdd2_global_lower (Fractions);
//                               fast: pdd2_global_error, a list of n entries, None or why the
//                               engine declined pdd2_global alone (then its row is NaN)
//   pdd2_global_grad            (if `gradient`, fast only) (n, 8, 3) float64, A's vertices first;
//                               NaN where pdd2_global is
//   error                       a list of n entries, None or why record j was rejected
// A rejected record's row: values and positions NaN (exact: None), labels "", intersecting
// False. Construct and add_to() with the GIL held; put() of a double record touches only the
// arrays' memory and may run without the GIL; put() of an exact record needs the GIL. Rows are
// put by one thread at a time.
class RecordColumns {
 public:
  RecordColumns(std::size_t n, bool exact, unsigned values, bool positions, bool global = false,
                bool gradient = false)
      : n_(static_cast<py::ssize_t>(n)), exact_(exact), values_(values), positions_(positions),
        intersecting_(n_) {
    if (gradient && !exact_) {
      global_grad_ = py::array_t<double>({n_, py::ssize_t{8}, py::ssize_t{3}});
      out_global_grad_ = global_grad_->mutable_data();
    }
    if (global && exact_) {
      for (auto* l : {&exact_global_, &exact_global_normal_, &exact_global_q1_[0], &exact_global_q1_[1],
                       &exact_global_lower_})
        *l = py::list(n_);
    }
    if (global && !exact_) {  // definitions §9: value (n,), normal (n, 3), positions (n, 4, 3)
      global_value_ = py::array_t<double>(n_);
      global_normal_ = py::array_t<double>({n_, py::ssize_t{3}});
      global_q1_[0] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
      global_q1_[1] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
      out_global_ = global_value_->mutable_data();
      out_global_normal_ = global_normal_->mutable_data();
      out_global_q1_[0] = global_q1_[0]->mutable_data();
      out_global_q1_[1] = global_q1_[1]->mutable_data();
    }
    for (std::size_t k = 0; k < pdd::kValueCount; ++k) {
      if (!has_value(k)) continue;
      if (exact_)
        exact_values_[k] = py::list(n_);
      else
        values_out_[k] = py::array_t<double>(n_);
      if (pdd::kLabelOfValue[k] >= 0) {
        auto& l = labels_[pdd::kLabelOfValue[k]];
        l = py::array(py::dtype("<U" + std::to_string(kLabelChars)), std::vector<py::ssize_t>{n_});
        std::memset(l->mutable_data(), 0, n * kLabelChars * sizeof(std::uint32_t));
      }
    }
    if (positions_) {
      if (exact_) {
        exact_q1_[0] = py::list(n_), exact_q1_[1] = py::list(n_);
      } else {
        q1_[0] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
        q1_[1] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
      }
    }
    // Raw pointers, so that put() of a double record calls nothing of Python's.
    out_intersecting_ = intersecting_.mutable_data();
    for (std::size_t k = 0; k < pdd::kValueCount; ++k)
      out_values_[k] = values_out_[k] ? values_out_[k]->mutable_data() : nullptr;
    for (std::size_t l = 0; l < pdd::kLabelCount; ++l)
      out_labels_[l] = labels_[l] ? static_cast<std::uint32_t*>(labels_[l]->mutable_data()) : nullptr;
    for (int s = 0; s < 2; ++s) out_q1_[s] = q1_[s] ? q1_[s]->mutable_data() : nullptr;
  }

  void put(std::size_t j, const pdd::PairResult<double>& r) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    put_common(j, r);
    for (std::size_t k = 0; k < pdd::kValueCount; ++k)
      if (out_values_[k]) out_values_[k][j] = r.error ? nan : pdd::record_value(r, k);
    const pdd::Positions<double>* q[2] = {&r.q1_A, &r.q1_B};
    for (int s = 0; s < 2; ++s)
      if (out_q1_[s])
        for (int i = 0; i < 4; ++i)
          for (int c = 0; c < 3; ++c) out_q1_[s][(j * 4 + i) * 3 + c] = r.error ? nan : (*q[s])[i][c];
    if (out_global_) {
      out_global_[j] = r.error ? nan : r.pdd2_global;
      for (int c = 0; c < 3; ++c)
        out_global_normal_[j * 3 + c] = (r.error || !r.pdd2_global_normal) ? nan : (*r.pdd2_global_normal)[c];
      const pdd::Positions<double>* g[2] = {&r.q1_A_global, &r.q1_B_global};
      for (int s = 0; s < 2; ++s)
        for (int i = 0; i < 4; ++i)
          for (int c = 0; c < 3; ++c) out_global_q1_[s][(j * 4 + i) * 3 + c] = r.error ? nan : (*g[s])[i][c];
      if (!r.error && r.pdd2_global_error) global_errors_.emplace_back(j, *r.pdd2_global_error);
    }
    if (out_global_grad_)
      for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c)
          out_global_grad_[(j * 8 + i) * 3 + c] = (r.error || !r.pdd2_global_grad) ? nan : (*r.pdd2_global_grad)[i][c];
  }

  void put(std::size_t j, const pdd::PairResult<pdd::Rational>& r) {  // GIL held
    put_common(j, r);
    const auto J = static_cast<py::ssize_t>(j);
    for (std::size_t k = 0; k < pdd::kValueCount; ++k)
      if (exact_values_[k])
        (*exact_values_[k])[J] = r.error ? py::object(py::none()) : number(pdd::record_value(r, k));
    const pdd::Positions<pdd::Rational>* q[2] = {&r.q1_A, &r.q1_B};
    for (int s = 0; s < 2; ++s)
      if (exact_q1_[s]) (*exact_q1_[s])[J] = r.error ? py::object(py::none()) : py::object(positions(*q[s]));
    if (exact_global_) {
      const py::object none = py::none();
      (*exact_global_)[J] = r.error ? none : number(r.pdd2_global);
      py::object normal = none;
      if (!r.error && r.pdd2_global_normal) {
        py::list n;
        for (const auto& c : *r.pdd2_global_normal) n.append(number(c));
        normal = n;
      }
      (*exact_global_normal_)[J] = normal;
      const pdd::Positions<pdd::Rational>* g[2] = {&r.q1_A_global, &r.q1_B_global};
      for (int s = 0; s < 2; ++s) (*exact_global_q1_[s])[J] = r.error ? none : py::object(positions(*g[s]));
      (*exact_global_lower_)[J] = (r.error || !r.pdd2_global_lower) ? none : number(*r.pdd2_global_lower);
    }
  }

  void add_to(py::dict& d) const {
    d["intersecting"] = intersecting_;
    for (std::size_t k = 0; k < pdd::kValueCount; ++k) {
      if (values_out_[k]) d[pdd::kValueKeys[k]] = *values_out_[k];
      if (exact_values_[k]) d[pdd::kValueKeys[k]] = *exact_values_[k];
    }
    for (std::size_t l = 0; l < pdd::kLabelCount; ++l)
      if (labels_[l]) d[pdd::kLabelKeys[l]] = *labels_[l];
    const char* q1_keys[2] = {"q1_A", "q1_B"};
    for (int s = 0; s < 2; ++s) {
      if (q1_[s]) d[q1_keys[s]] = *q1_[s];
      if (exact_q1_[s]) d[q1_keys[s]] = *exact_q1_[s];
    }
    if (global_value_) {
      d["pdd2_global"] = *global_value_;
      d["pdd2_global_normal"] = *global_normal_;
      d["q1_A_global"] = *global_q1_[0];
      d["q1_B_global"] = *global_q1_[1];
      d["pdd2_global_error"] = error_column(global_errors_);
    }
    if (global_grad_) d["pdd2_global_grad"] = *global_grad_;
    if (exact_global_) {  // in the order `pdd solve` writes them
      d["pdd2_global"] = *exact_global_;
      d["pdd2_global_normal"] = *exact_global_normal_;
      d["q1_A_global"] = *exact_global_q1_[0];
      d["q1_B_global"] = *exact_global_q1_[1];
      d["pdd2_global_lower"] = *exact_global_lower_;
    }
    d["error"] = error_column(errors_);
  }

 private:
  // n entries: None, or the message of row j
  py::list error_column(const std::vector<std::pair<std::size_t, std::string>>& messages) const {
    py::list out(n_);
    for (py::ssize_t j = 0; j < n_; ++j) out[j] = py::none();
    for (const auto& [j, msg] : messages) out[static_cast<py::ssize_t>(j)] = py::str(msg);
    return out;
  }

  bool has_value(std::size_t k) const { return values_ & (1u << k); }

  template <class R>
  void put_common(std::size_t j, const pdd::PairResult<R>& r) {
    if (r.error) errors_.emplace_back(j, *r.error);
    out_intersecting_[j] = !r.error && r.intersecting;
    for (std::size_t l = 0; l < pdd::kLabelCount; ++l) {
      const auto& label = pdd::record_label(r, l);
      if (!out_labels_[l] || r.error || !label) continue;
      const std::string s = label->str();
      for (std::size_t c = 0; c < s.size() && c < std::size_t(kLabelChars); ++c)
        out_labels_[l][j * kLabelChars + c] = static_cast<unsigned char>(s[c]);
    }
  }

  py::ssize_t n_;
  bool exact_;
  unsigned values_;
  bool positions_;
  py::array_t<bool> intersecting_;
  // Empty where not a column (a default pybind11 array or list is not a null handle).
  std::array<std::optional<py::array_t<double>>, pdd::kValueCount> values_out_;
  std::array<std::optional<py::list>, pdd::kValueCount> exact_values_;
  std::array<std::optional<py::array>, pdd::kLabelCount> labels_;
  std::array<std::optional<py::array_t<double>>, 2> q1_;
  std::array<std::optional<py::list>, 2> exact_q1_;
  bool* out_intersecting_ = nullptr;
  std::array<double*, pdd::kValueCount> out_values_{};
  std::array<std::uint32_t*, pdd::kLabelCount> out_labels_{};
  std::array<double*, 2> out_q1_{};
  std::vector<std::pair<std::size_t, std::string>> errors_, global_errors_;
  std::optional<py::array_t<double>> global_value_, global_normal_;
  std::array<std::optional<py::array_t<double>>, 2> global_q1_;
  double* out_global_ = nullptr;
  double* out_global_normal_ = nullptr;
  std::array<double*, 2> out_global_q1_{};
  std::optional<py::array_t<double>> global_grad_;
  double* out_global_grad_ = nullptr;
  std::optional<py::list> exact_global_, exact_global_normal_, exact_global_lower_;
  std::array<std::optional<py::list>, 2> exact_global_q1_;
};

}  // namespace pdd_python
