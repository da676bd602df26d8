#pragma once
/// @file
/// Tpetra/Kokkos aliases. Debian's Tpetra is instantiated only for the default template
/// arguments (double, int, long long, Serial): use these everywhere (PLATFORM.md).
#include <Kokkos_Core.hpp>
#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

/// GPHR's namespace: gradient-preserving hyper-reduction of Hamiltonian systems on Trilinos (Pagliantini & Vismara).
namespace gphr {

using Scalar = double;  ///< Scalar type of every state, basis and matrix.
using Map = Tpetra::Map<>;  ///< Tpetra map with the default template arguments.
using LO = Map::local_ordinal_type;  ///< Local ordinal (index of an entry on this rank).
using GO = Map::global_ordinal_type;  ///< Global ordinal (index of an entry of y or a row of G over all ranks).
using Node = Map::node_type;  ///< Kokkos node of the Tpetra objects.
using Vector = Tpetra::Vector<Scalar>;  ///< Distributed vector (a state y in R^{2n}, a vector of size d).
using MultiVector = Tpetra::MultiVector<Scalar>;  ///< Distributed multivector (snapshot matrices, the basis A).
using CrsGraph = Tpetra::CrsGraph<>;  ///< Sparsity graph of a distributed sparse matrix.
using CrsMatrix = Tpetra::CrsMatrix<Scalar>;  ///< Distributed sparse matrix (L, J_G, Hessians, Newton matrices).
using Operator = Tpetra::Operator<Scalar>;  ///< Tpetra operator (a linear map applied without forming it).
using Import = Tpetra::Import<>;  ///< Tpetra importer (owned -> overlapping distribution).
using Export = Tpetra::Export<>;  ///< Tpetra exporter (overlapping -> owned distribution).
using Comm = Teuchos::Comm<int>;  ///< MPI communicator.
using Teuchos::RCP;  ///< Shared ownership pointer (Teuchos::RCP).
using Teuchos::rcp;  ///< Makes an RCP (Teuchos::rcp).

/// Row kernels run on the host execution space: Debian's Kokkos has only Serial, and a Kokkos
/// built with OpenMP threads these loops unchanged. (A CUDA build would need device views of the
/// stencil buffers; see doc/design.md, 'Row kernels and assembly'.)
using ExecSpace = Kokkos::DefaultHostExecutionSpace;
/// Host view of scalars (stencil values, G_i, gradients, Hessians).
using HostView1 = Kokkos::View<Scalar*, Kokkos::HostSpace>;
using IndexView = Kokkos::View<LO*, Kokkos::HostSpace>;  ///< Host view of local indices.
using OffsetView = Kokkos::View<size_t*, Kokkos::HostSpace>;  ///< Host view of offsets into packed stencil arrays.

}  // namespace gphr
