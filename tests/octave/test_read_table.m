% tables/matlab/wrc_read_table.m in Octave, on tables whose values are known in closed form
% (tests/integration/make_table.cpp): run by ctest as
%   octave-cli test_read_table.m SOURCE_DIR WRC_BINARY WHEELSET_TABLE SMALL_TABLE
args = argv();
[source_dir, wrc_binary, wheelset_table, small_table] = deal(args{1:4});
addpath(fullfile(source_dir, 'tables', 'matlab'));

% tests/runtime/wheelset_table.h: WheelsetFunction, output k = 0 .. 7 on (y, roll, yaw, spin).
f = @(k, y, roll, yaw, spin) 100 * (k + 1) + (10 + k) * y + 2000 * (k - 3) * roll + ...
    5000 * (2 * k - 5) * yaw + 30000 * (mod(k, 3) - 1) * spin;
tolerance = 1e-9;

% roll and yaw both have 5 nodes: the order comes from `wrc info --json`.
t = wrc_read_table(wheelset_table, wrc_binary);
assert(isequal(t.axis_names, {'y', 'roll', 'yaw', 'spin'}));
assert(isequal(size(t.outputs.fy), [41 5 5 9]));
assert(isequal(size(t.status), [41 5 5 9]) && all(t.status(:) == 0));
[y, roll, yaw, spin] = ndgrid(t.axes{:});
assert(max(abs(t.outputs.fy(:) - f(1, y(:), roll(:), yaw(:), spin(:)))) < tolerance * 1e3);
assert(max(abs(t.outputs.mz(:) - f(5, y(:), roll(:), yaw(:), spin(:)))) < tolerance * 1e3);
% Multilinear interpolation reproduces the affine outputs between nodes.
q = [3.3, 0.0011, -0.004, 0.0025];
fy = interpn(t.axes{:}, t.outputs.fy, q(1), q(2), q(3), q(4), 'linear');
assert(abs(fy - f(1, q(1), q(2), q(3), q(4))) < tolerance * 1e3);

% Without h5readatt and without wrc, equal axis lengths cannot be ordered: a clear error.
failed = false;
try
  wrc_read_table(wheelset_table, '/nonexistent/wrc');
catch err
  failed = strcmp(err.identifier, 'wrc_read_table:order');
end
assert(failed);

% Axes of different lengths (5 and 3): the shape orders them, wrc is not needed.
s = wrc_read_table(small_table, '/nonexistent/wrc');
assert(isequal(s.axis_names, {'y', 'spin'}));
fx = interpn(s.axes{:}, s.outputs.fx, 0.5, 0.005, 'linear');
assert(abs(fx - 3.625) < 1e-12);
printf('wrc_read_table: 4-axis and 2-axis tables read in axis order, fy = %.6f\n', fy);
