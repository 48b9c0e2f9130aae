#!/usr/bin/python3
"""A client in another language, generated from our proto by Debian's Python gRPC tools.

Compiles proto/aperture/v1/*.proto with `python3 -m grpc_tools.protoc` (python3-grpc-tools, whose
protoc refuses proto3 `optional`, so the proto uses wrapper messages), starts a real
aperture-server on loopback, and through the generated stubs: reads the server's info, loads the built-in demo, renders a frame
and checks it pixel for pixel against `aperture-render` of the same camera and options (both read
with OpenImageIO's Python module), and sends the wrapper field raytrace_max_depth out of range,
which must come back INVALID_ARGUMENT naming the field.

Usage: python_client_test.py --proto DIR --server BIN --render BIN
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def generate_stubs(proto_dir, out_dir):
    protos = [os.path.join(proto_dir, "aperture", "v1", name)
              for name in ("scene.proto", "render_service.proto")]
    # grpc_tools ships the well-known types (google/protobuf/wrappers.proto) beside its protoc.
    import grpc_tools
    well_known = os.path.join(os.path.dirname(grpc_tools.__file__), "_proto")
    result = subprocess.run(
        [sys.executable, "-m", "grpc_tools.protoc", "-I" + proto_dir, "-I" + well_known,
         "--python_out=" + out_dir, "--grpc_python_out=" + out_dir] + protos,
        capture_output=True, text=True, check=False)
    if result.returncode != 0:
        fail("grpc_tools.protoc refused the proto:\n" + result.stderr)
    print("generated Python stubs with grpc_tools.protoc")


def start_server(server_bin, store):
    process = subprocess.Popen(
        [server_bin, "--listen", "127.0.0.1:0", "--threads", "2", "--store", store],
        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    deadline = time.time() + 30
    while time.time() < deadline:
        line = process.stdout.readline()
        if line.startswith("listening on "):
            return process, line.split()[-1]
        if process.poll() is not None:
            break
    process.kill()
    fail("the server did not start")


def pixels(path):
    import OpenImageIO as oiio
    image = oiio.ImageBuf(path)
    if image.has_error:
        fail("cannot read %s: %s" % (path, image.geterror()))
    return image.spec().width, image.spec().height, image.get_pixels(oiio.FLOAT)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--proto", required=True)
    parser.add_argument("--server", required=True)
    parser.add_argument("--render", required=True)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as work:
        generate_stubs(args.proto, work)
        sys.path.insert(0, work)
        import grpc
        from aperture.v1 import render_service_pb2 as service
        from aperture.v1 import render_service_pb2_grpc as service_grpc
        from aperture.v1 import scene_pb2 as scene

        server, address = start_server(args.server, os.path.join(work, "store"))
        try:
            channel = grpc.insecure_channel(
                address, options=[("grpc.max_receive_message_length", -1)])
            stub = service_grpc.RenderStub(channel)
            info = stub.GetServerInfo(service.GetServerInfoRequest(), timeout=10)
            print("server info: version %s" % info.version)
            if not info.version:
                fail("GetServerInfo carries no version")

            loaded = stub.LoadScene(service.LoadSceneRequest(builtin_scene="demo"), timeout=60)
            if not loaded.scene_id or loaded.polygons == 0:
                fail("LoadScene of the demo answered %s" % loaded)

            camera = scene.Camera(position=scene.Vec3(x=0, y=20, z=300), yaw_deg=5,
                                  pitch_deg=-6, roll_deg=1, vertical_fov_deg=60)
            options = scene.RenderOptions(width=96, height=54,
                                          anti_aliasing=scene.ANTI_ALIASING_TENT2,
                                          filter=scene.TEXTURE_FILTER_TRILINEAR)
            frame = stub.RenderFrame(service.RenderFrameRequest(
                scene_id=loaded.scene_id, camera=camera, options=options), timeout=60)
            served = os.path.join(work, "served.exr")
            with open(served, "wb") as out:
                out.write(frame.exr)

            local = os.path.join(work, "local.exr")
            subprocess.run([args.render, "--scene=demo", "--camera=0,20,300,5,-6,1", "--fov=60",
                            "--size=96x54", "--aa=tent2", "--filter=trilinear", "--nopreview",
                            "--threads=2", "--store=" + os.path.join(work, "store"), "-o", local],
                           check=True, capture_output=True)
            a, b = pixels(served), pixels(local)
            if a[:2] != (96, 54) or a[:2] != b[:2]:
                fail("sizes differ: served %s, local %s" % (a[:2], b[:2]))
            if not (a[2] == b[2]).all():
                fail("the frame served to the Python client differs from aperture-render's")
            print("RenderFrame from Python: 96x54, pixel-identical to aperture-render")

            options.mode = scene.RENDER_MODE_RAYTRACE
            options.raytrace_max_depth.value = 9
            try:
                stub.RenderFrame(service.RenderFrameRequest(
                    scene_id=loaded.scene_id, camera=camera, options=options), timeout=60)
                fail("raytrace_max_depth 9 was accepted")
            except grpc.RpcError as error:
                if error.code() != grpc.StatusCode.INVALID_ARGUMENT or \
                        "raytrace_max_depth is 9" not in error.details():
                    fail("raytrace_max_depth 9 answered %s: %s" % (error.code(), error.details()))
            print("raytrace_max_depth 9 (a wrapper field) refused: INVALID_ARGUMENT")
        finally:
            server.terminate()
            server.wait(timeout=30)
    print("PASS")


if __name__ == "__main__":
    main()
