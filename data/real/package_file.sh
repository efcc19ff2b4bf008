# Shared by the corpora's build.sh scripts (sourced, after they set `tmp` to a scratch folder).
# package_file PACKAGE PATH: a file of a Debian package, the installed one, else one unpacked
# from `apt-get download` into "$tmp/PACKAGE".
package_file() {
  local package="$1" rel="$2"
  if [ -f "/$rel" ]; then
    echo "/$rel"
    return
  fi
  if [ ! -d "$tmp/$package" ]; then
    (cd "$tmp" && apt-get download "$package" >/dev/null 2>&1 && dpkg -x "$package"_*.deb "$package")
  fi
  echo "$tmp/$package/$rel"
}
