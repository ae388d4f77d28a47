#include <cholmod.h>
#include <dlfcn.h>
#include <gtest/gtest.h>

#include "BlockSystem.h"
#include "SparseCholesky.h"

// The licence (docs/licence.md): the solver must reach only CHOLMOD's LGPL modules. A call to
// the GPL Supernodal module happens inside cholmod_factorize, out of sight of the binaries'
// imports, so these definitions take its place (libcholmod calls it through its PLT) and count.
namespace {
int supernodalCalls = 0;
}

extern "C" int cholmod_super_numeric(cholmod_sparse* A, cholmod_sparse* F, double beta[2],
                                     cholmod_factor* L, cholmod_common* c) {
    ++supernodalCalls;
    using Real =
        int (*)(cholmod_sparse*, cholmod_sparse*, double*, cholmod_factor*, cholmod_common*);
    static Real real = reinterpret_cast<Real>(dlsym(RTLD_NEXT, "cholmod_super_numeric"));
    return real(A, F, beta, L, c);
}

extern "C" int cholmod_l_super_numeric(cholmod_sparse* A, cholmod_sparse* F, double beta[2],
                                       cholmod_factor* L, cholmod_common* c) {
    ++supernodalCalls;
    using Real =
        int (*)(cholmod_sparse*, cholmod_sparse*, double*, cholmod_factor*, cholmod_common*);
    static Real real = reinterpret_cast<Real>(dlsym(RTLD_NEXT, "cholmod_l_super_numeric"));
    return real(A, F, beta, L, c);
}

using namespace boneless;

TEST(CholmodLicence, SolverFactorisesWithoutCholmodsGplSupernodalModule) {
    const int n = 300;
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) {
        entries.emplace_back(i, i, 4.0);
        if (i + 1 < n) entries.emplace_back(i + 1, i, -1.0), entries.emplace_back(i, i + 1, -1.0);
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(entries.begin(), entries.end());
    SparseCholesky cholesky;
    ASSERT_TRUE(cholesky.factorize(A));
    const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(n, 2);
    EXPECT_LT((A * cholesky.solve(B) - B).norm(), 1e-9);

    std::vector<std::vector<int>> chain;
    for (int v = 0; v + 2 < n; ++v) chain.push_back({v, v + 1, v + 2});
    BlockSystem system(n, Stencils(chain));
    system.clear();
    for (int v = 0; v < n; ++v) system.addDiagonal(v, 2.0 * Mat3::Identity());
    ASSERT_TRUE(system.factorize(0.0));

    EXPECT_EQ(supernodalCalls, 0);
}
