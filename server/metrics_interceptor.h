// The gRPC server interceptor that feeds ServiceMetrics: it sees every call's status (RPCs by
// method and code, UNAUTHENTICATED refusals, wherever the refusal is decided), and for
// RenderFrame and RenderStream each request (its render mode) and each answer before and after
// it is handed to the transport (outcome, status, stage times, the send time). The handlers
// carry no metrics code. Installed only with --metrics-listen.
#pragma once

#include <grpcpp/support/server_interceptor.h>

#include <memory>
#include <vector>

#include "service_metrics.h"

namespace aperture {

// One factory, for ServerBuilder::experimental().SetInterceptorCreators; `metrics` must outlive
// the server.
std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> MetricsInterceptorFactory(
    ServiceMetrics& metrics);

}  // namespace aperture
