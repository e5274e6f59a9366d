#include "core/gsl/integration.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "core/gsl/error.h"

namespace wrc::gsl {
namespace {

struct WorkspaceDeleter {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};
using Workspace = std::unique_ptr<gsl_integration_workspace, WorkspaceDeleter>;

Workspace AllocateWorkspace(std::size_t max_intervals) {
  Workspace workspace(gsl_integration_workspace_alloc(max_intervals));
  // With the abort handler off, GSL reports a bad size or a failed allocation by returning null.
  if (!workspace) throw GslError("gsl_integration_workspace_alloc", GSL_ENOMEM);
  return workspace;
}

using Integrand = GuardedCallback;

gsl_function AsGsl(Integrand& integrand) { return gsl_function{&Integrand::Call, &integrand}; }

}  // namespace

IntegrationResult IntegrateQags(const std::function<double(double)>& f, double lo, double hi,
                                const IntegrationOptions& options) {
  DisableAbortOnError();
  Workspace workspace = AllocateWorkspace(options.max_intervals);
  Integrand integrand{&f, nullptr};
  gsl_function function = AsGsl(integrand);
  IntegrationResult result;
  const int status = gsl_integration_qags(&function, lo, hi, options.abs_tolerance,
                                          options.rel_tolerance, options.max_intervals,
                                          workspace.get(), &result.value, &result.abs_error);
  integrand.RethrowIfFailed();
  CheckStatus(status, "gsl_integration_qags");
  return result;
}

IntegrationResult IntegrateQagp(const std::function<double(double)>& f, std::vector<double> points,
                                const IntegrationOptions& options) {
  if (points.size() < 2) {
    throw std::invalid_argument("IntegrateQagp: needs at least the two end points");
  }
  DisableAbortOnError();
  Workspace workspace = AllocateWorkspace(options.max_intervals);
  Integrand integrand{&f, nullptr};
  gsl_function function = AsGsl(integrand);
  IntegrationResult result;
  const int status = gsl_integration_qagp(
      &function, points.data(), points.size(), options.abs_tolerance, options.rel_tolerance,
      options.max_intervals, workspace.get(), &result.value, &result.abs_error);
  integrand.RethrowIfFailed();
  CheckStatus(status, "gsl_integration_qagp");
  return result;
}

IntegrationResult IntegrateCauchy(const std::function<double(double)>& f, double lo, double hi,
                                  double pole, const IntegrationOptions& options) {
  DisableAbortOnError();
  Workspace workspace = AllocateWorkspace(options.max_intervals);
  Integrand integrand{&f, nullptr};
  gsl_function function = AsGsl(integrand);
  IntegrationResult result;
  const int status = gsl_integration_qawc(&function, lo, hi, pole, options.abs_tolerance,
                                          options.rel_tolerance, options.max_intervals,
                                          workspace.get(), &result.value, &result.abs_error);
  integrand.RethrowIfFailed();
  CheckStatus(status, "gsl_integration_qawc");
  return result;
}

namespace {

// [lo, hi] cut at the breakpoints strictly inside it, in increasing order.
std::vector<double> SplitRange(double lo, double hi, const std::vector<double>& breaks) {
  std::vector<double> edges{lo};
  std::vector<double> inside;
  for (double b : breaks) {
    if (b > std::min(lo, hi) && b < std::max(lo, hi)) inside.push_back(b);
  }
  // Keep the direction of [lo, hi] so that a reversed range still gives −∫.
  if (lo <= hi) {
    std::sort(inside.begin(), inside.end());
  } else {
    std::sort(inside.rbegin(), inside.rend());
  }
  inside.erase(std::unique(inside.begin(), inside.end()), inside.end());
  edges.insert(edges.end(), inside.begin(), inside.end());
  edges.push_back(hi);
  return edges;
}

}  // namespace

IntegrationResult Integrate2d(const std::function<double(double, double)>& f, double xlo,
                              double xhi, double ylo, double yhi, const IntegrationOptions& options,
                              const std::vector<double>& x_breaks,
                              const std::vector<double>& y_breaks) {
  const std::vector<double> x_edges = SplitRange(xlo, xhi, x_breaks);
  const std::vector<double> y_edges = SplitRange(ylo, yhi, y_breaks);
  const double width = std::fabs(xhi - xlo);
  // Share the absolute goal out: an inner error δ per unit of x adds up to δ·width, and the x
  // pieces get goals in proportion to their widths, so both levels together stay within about
  // 2·abs_tolerance.
  IntegrationOptions inner_options = options;
  inner_options.abs_tolerance = width > 0.0 ? options.abs_tolerance / width : 0.0;
  double largest_inner_error = 0.0;
  const std::function<double(double)> inner = [&](double x) {
    double sum = 0.0;
    for (std::size_t j = 0; j + 1 < y_edges.size(); ++j) {
      const IntegrationResult piece = IntegrateQags([&](double y) { return f(x, y); }, y_edges[j],
                                                    y_edges[j + 1], inner_options);
      sum += piece.value;
      largest_inner_error = std::max(largest_inner_error, piece.abs_error);
    }
    return sum;
  };
  IntegrationResult total;
  for (std::size_t i = 0; i + 1 < x_edges.size(); ++i) {
    const double piece_width = std::fabs(x_edges[i + 1] - x_edges[i]);
    IntegrationOptions outer_options = options;
    outer_options.abs_tolerance = width > 0.0 ? options.abs_tolerance * piece_width / width : 0.0;
    largest_inner_error = 0.0;
    const IntegrationResult piece = IntegrateQags(inner, x_edges[i], x_edges[i + 1], outer_options);
    total.value += piece.value;
    total.abs_error += piece.abs_error +
                       piece_width * static_cast<double>(y_edges.size() - 1) * largest_inner_error;
  }
  return total;
}

}  // namespace wrc::gsl
