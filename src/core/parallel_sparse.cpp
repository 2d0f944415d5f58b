#include "core/parallel_sparse.hpp"

namespace particles {

void multiplySymmetric(WorkerPool* pool, const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& x,
                       Eigen::VectorXd& out) {
  out.resize(a.cols());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* values = a.valuePtr();
  forChunks(pool, size_t(a.cols()), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      double even = 0.0, odd = 0.0;
      int k = outer[i];
      for (; k + 1 < outer[i + 1]; k += 2) {
        even += values[k] * x[inner[k]];
        odd += values[k + 1] * x[inner[k + 1]];
      }
      if (k < outer[i + 1]) even += values[k] * x[inner[k]];
      out[Eigen::Index(i)] = even + odd;
    }
  });
}

double dotChunks(WorkerPool* pool, const Eigen::VectorXd& x, const Eigen::VectorXd& y, std::vector<double>& partials) {
  return sumChunks(pool, size_t(x.size()), kVectorChunk, partials, [&](size_t begin, size_t end) {
    const Eigen::Index n = Eigen::Index(end - begin);
    return x.segment(Eigen::Index(begin), n).dot(y.segment(Eigen::Index(begin), n));
  });
}

}  // namespace particles
