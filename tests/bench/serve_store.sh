# Sourced by the bench scripts: serve_store STORE SERVER_DIR serves the store directory STORE with
# Debian's nginx on a free loopback port (tests/store/nginx.conf, nginx's files in SERVER_DIR,
# made anew), sets `url` to its address, and stops nginx by its PID when the script exits.
serve_store() {
  local store=$1 server=$2 port user=""
  rm -rf "$server"
  mkdir -p "$server/tmp"
  ln -s "$store" "$server/www"
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  if [[ $(id -u) -eq 0 ]]; then user="user root;"; fi
  sed -e "s|@DIR@|$server|g" -e "s|@PORT@|$port|g" -e "s|@USER@|$user|" \
    "$(dirname "${BASH_SOURCE[0]}")/../store/nginx.conf" >"$server/nginx.conf"
  nginx -p "$server" -e "$server/error.log" -c "$server/nginx.conf" &
  nginx_pid=$!
  trap 'kill $nginx_pid; wait $nginx_pid 2>/dev/null || true' EXIT
  url=http://127.0.0.1:$port/pub
  until curl -sf -o /dev/null "$url/MANIFEST"; do sleep 0.05; done
}
