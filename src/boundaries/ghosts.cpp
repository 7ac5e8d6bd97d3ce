#include "sphark/boundaries/ghosts.hpp"

#include <sstream>
#include <stdexcept>

namespace sphark {

std::string GhostReport::message() const {
  if (invalid == 0) return {};
  std::ostringstream os;
  os << invalid << " particle(s) without ghost: " << to_string(first_status) << " (first: particle "
     << first_invalid << " at s = " << first_invalid_s << ", cos u = " << first_invalid_cos_u << ")";
  return os.str();
}

namespace {
template <int D> Vec<D> origin(const Plane<D>& w) { return w.point; }
template <int D> Vec<D> origin(const Cylinder<D>& w) { return w.centre; }
inline Vec<3> origin(const Sphere& w) { return w.centre; }
inline Vec<3> origin(const Torus& w) { return w.centre; }
}  // namespace

template <int D>
void GhostLayer<D>::reserve(std::size_t n) {
  if (n <= capacity()) return;
  x_.resize(D * n);
  v_.resize(D * n);
  s_.resize(n);
  src_.resize(n);
}

template <int D>
GhostReport GhostLayer<D>::append(const Wall<D>& wall, const Real* x, const Real* v, std::size_t n,
                                  const GhostOptions& opt, const PeriodicBox<D>* box) {
  reserve(count_ + n);  // at most one ghost per particle: no allocation once the capacity is there
  GhostReport rep;
  std::visit(
      [&](const auto& w) {
        const Vec<D> o = origin(w);
        for (std::size_t i = 0; i < n; ++i) {
          Vec<D> xi = Eigen::Map<const Vec<D>>(x + D * i);
          if (box) xi = o + box->minimum_image(xi - o);
          const WallPoint<D> p = w.locate(xi);
          if (!(p.s > -opt.width)) continue;
          if (p.s > 0) {
            ++rep.outside;
            continue;
          }
          const MapResult m = opt.map == GhostMap::Mirror ? mirror_map(p.s) : w.map(p);
          if (!m.ok()) {
            if (rep.invalid++ == 0) {
              rep.first_invalid = i;
              rep.first_invalid_s = p.s;
              rep.first_invalid_cos_u = p.cos_u;
              rep.first_status = m.status;
            }
            continue;
          }
          Vec<D> g = xi + (m.psi - p.s) * p.normal;  // same normal line, s -> psi(s)
          if (box) g = box->wrap(g);
          const std::size_t k = count_++;
          Eigen::Map<Vec<D>>(x_.data() + D * k) = g;
          Eigen::Map<Vec<D>> vg(v_.data() + D * k);
          if (v) {
            const Vec<D> vi = Eigen::Map<const Vec<D>>(v + D * i);
            vg = opt.velocity == VelocityBc::NoSlip ? Vec<D>(-vi) : Vec<D>(vi - 2 * vi.dot(p.normal) * p.normal);
          } else {
            vg.setZero();
          }
          s_[k] = m.psi;
          src_[k] = static_cast<std::uint32_t>(i);
          ++rep.generated;
        }
      },
      wall);
  if (rep.invalid > 0 && opt.on_invalid == OnInvalid::Throw) throw std::domain_error("ghosts: " + rep.message());
  return rep;
}

template class GhostLayer<2>;
template class GhostLayer<3>;

}  // namespace sphark
