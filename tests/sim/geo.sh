# tests/sim/geo.sh: for the `cumulo ig` tests, sourced: the eyepoint a host's geodetic pose should give, worked
# here in awk from WGS84 (not from platform/sim/geodetic.c), and a comparison of comma-separated vectors.
# wgs84 LAT LON ALT HEADING PITCH ROLL [VIEW] (origin in $LAT0 $LON0 $ALT0) prints "x,y,z fx,fy,fz ux,uy,uz": the eye in
# world metres (east, up, south of the origin), where it looks and its up, local level: east and north of the origin
# from the ECEF of both points in the origin's east-north-up, up as the altitude above the origin's; the attitude as
# heading, pitch, roll in the aircraft's north-east-down frame, its axes against the aircraft's own east, up, north.
# VIEW "x,y,z,yaw" is a CIGI View Control: the eye that far along the aircraft's forward, right and down axes, turned
# by yaw about its down.
wgs84() {
  awk -v la=$1 -v lo=$2 -v h=$3 -v yw=$4 -v pt=$5 -v rl=$6 -v view="${7:-0,0,0,0}" -v la0=$LAT0 -v lo0=$LON0 \
      -v h0=$ALT0 'BEGIN {
    d = atan2(0, -1) / 180; a = 6378137; f = 1 / 298.257223563; e2 = f * (2 - f)
    ecef(la, lo, h, P); ecef(la0, lo0, h0, O)
    enu(la0, lo0, E, N, U)
    # the aircraft: NED at its point, heading yaw about down, pitch about the new right, roll about forward
    enu(la, lo, e, n, u)
    cy = cos(yw*d); sy = sin(yw*d); cp = cos(pt*d); sp = sin(pt*d); cr = cos(rl*d); sr = sin(rl*d)
    for (i = 1; i <= 3; i++) {
      fw[i] = cp*cy*n[i] + cp*sy*e[i] - sp*(-u[i])
      dn[i] = (cy*sp*cr + sy*sr)*n[i] + (sy*sp*cr - cy*sr)*e[i] + cp*cr*(-u[i])
      rt[i] = (cy*sp*sr - sy*cr)*n[i] + (sy*sp*sr + cy*cr)*e[i] + cp*sr*(-u[i])
    }
    split(view, v, ","); cv = cos(v[4]*d); sv = sin(v[4]*d)
    for (i = 1; i <= 3; i++) {
      D[i] = P[i] - O[i]
      off[i] = v[1]*fw[i] + v[2]*rt[i] + v[3]*dn[i]
      vf[i] = cv*fw[i] + sv*rt[i]
    }
    # local level: east and north of the origin from the ECEF difference, height = altitude above the origin,
    # the axes against the own east, up and north of the eye
    printf "%.3f,%.3f,%.3f ", dot(D,E) + dot(off,e), h - h0 + dot(off,u), -dot(D,N) - dot(off,n)
    printf "%.6f,%.6f,%.6f ", dot(vf,e), dot(vf,u), -dot(vf,n)
    printf "%.6f,%.6f,%.6f\n", -dot(dn,e), -dot(dn,u), dot(dn,n)
  }
  function ecef(la, lo, h, X,   s, c, nn) { s = sin(la*d); c = cos(la*d); nn = a / sqrt(1 - e2*s*s)
    X[1] = (nn+h)*c*cos(lo*d); X[2] = (nn+h)*c*sin(lo*d); X[3] = (nn*(1-e2)+h)*s }
  function enu(la, lo, E, N, U,   s, c, so, co) { s = sin(la*d); c = cos(la*d); so = sin(lo*d); co = cos(lo*d)
    E[1] = -so; E[2] = co; E[3] = 0; N[1] = -s*co; N[2] = -s*so; N[3] = c; U[1] = c*co; U[2] = c*so; U[3] = s }
  function dot(A, B) { return A[1]*B[1] + A[2]*B[2] + A[3]*B[3] }'
}
# close A B TOL: every comma-separated component within TOL
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { n = split(a, x, ","); m = split(b, y, ",");
  if (n != m || n == 0) exit 1; for (i = 1; i <= n; i++) { v = x[i] - y[i]; if (v < 0) v = -v; if (v > t) exit 1 } }'; }
