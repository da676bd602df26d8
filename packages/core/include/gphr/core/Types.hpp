#pragma once
// Tpetra/Kokkos aliases. Debian's Tpetra is instantiated only for the default template
// arguments (double, int, long long, Serial): use these everywhere (PLATFORM.md).
#include <Kokkos_Core.hpp>
#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

namespace gphr {

using Scalar = double;
using Map = Tpetra::Map<>;
using LO = Map::local_ordinal_type;
using GO = Map::global_ordinal_type;
using Node = Map::node_type;
using Vector = Tpetra::Vector<Scalar>;
using MultiVector = Tpetra::MultiVector<Scalar>;
using CrsGraph = Tpetra::CrsGraph<>;
using CrsMatrix = Tpetra::CrsMatrix<Scalar>;
using Operator = Tpetra::Operator<Scalar>;
using Import = Tpetra::Import<>;
using Export = Tpetra::Export<>;
using Comm = Teuchos::Comm<int>;
using Teuchos::RCP;
using Teuchos::rcp;

// Row kernels run on the host execution space: Debian's Kokkos has only Serial, and a Kokkos
// built with OpenMP threads these loops unchanged. (A CUDA build would need device views of the
// stencil buffers; see doc/design.md, 'Row kernels and assembly'.)
using ExecSpace = Kokkos::DefaultHostExecutionSpace;
using HostView1 = Kokkos::View<Scalar*, Kokkos::HostSpace>;
using IndexView = Kokkos::View<LO*, Kokkos::HostSpace>;
using OffsetView = Kokkos::View<size_t*, Kokkos::HostSpace>;

}  // namespace gphr
