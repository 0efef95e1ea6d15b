# The image the Kubernetes manifests of docs/scenes.md run: the elcon binary
# and the example scenes under /work.
#
#   docker build -t elcon:latest .
#   docker run --rm -v "$PWD/out:/work/out" elcon:latest run examples/scenes/example1-spheres.toml
FROM rust:1.89-bookworm AS build
WORKDIR /src
COPY . .
RUN cargo build --release --locked --bin elcon

FROM debian:bookworm-slim
COPY --from=build /src/target/release/elcon /usr/local/bin/elcon
COPY examples/scenes /work/examples/scenes
WORKDIR /work
ENTRYPOINT ["elcon"]
