function t = wrc_read_table(file, wrc_command)
% WRC_READ_TABLE  Reads a wrc table (wrc generate's HDF5 file) in MATLAB or in Octave.
%
%   t = wrc_read_table('demo.h5')
%   t = wrc_read_table('demo.h5', '/path/to/wrc')
%
%   t.axis_names  cell array of axis names, in dimension order (the /axes attribute 'order')
%   t.axes        cell array of column vectors: the nodes of each axis, in that order
%   t.outputs     struct: one array per output, size = the axis lengths in order, so that
%                 t.outputs.fy(i, j) belongs to t.axes{1}(i), t.axes{2}(j)
%   t.status      /status likewise (0 ok, 1 no contact, 2 not converged, 3 error)
%
% HDF5 lists dimensions slowest first and MATLAB and Octave fastest first, so every array comes
% back with its dimensions reversed; they are permuted back here. MATLAB reads the axis order
% with h5readatt. Octave as shipped has no h5readatt (its load -hdf5 reads datasets but no
% attributes), so the order comes from the data's shape where the axis lengths tell the axes
% apart, and otherwise from `wrc info --json` (wrc_command, default 'wrc' on the PATH).
  if nargin < 2
    wrc_command = 'wrc';
  end
  if exist('h5readatt') == 2 || exist('h5readatt') == 5
    t = read_with_h5read(file);
  else
    t = read_with_load(file, wrc_command);
  end
end

function t = read_with_h5read(file)
  names = h5readatt(file, '/axes', 'order');
  if ischar(names)
    names = cellstr(names);
  end
  t.axis_names = reshape(names, 1, []);
  n = numel(names);
  t.axes = cell(1, n);
  for k = 1:n
    t.axes{k} = double(h5read(file, ['/axes/' names{k}]));
    t.axes{k} = t.axes{k}(:);
  end
  info = h5info(file, '/outputs');
  t.outputs = struct();
  for k = 1:numel(info.Datasets)
    name = info.Datasets(k).Name;
    t.outputs.(name) = in_axis_order(h5read(file, ['/outputs/' name]), n);
  end
  t.status = in_axis_order(h5read(file, '/status'), n);
end

function t = read_with_load(file, wrc_command)
  data = load('-hdf5', file);
  names = fieldnames(data.axes);  % sorted by name, not in dimension order
  lengths = zeros(1, numel(names));
  for k = 1:numel(names)
    lengths(k) = numel(data.axes.(names{k}));
  end
  order = order_from_shape(size(data.status), names, lengths);
  if isempty(order)
    order = order_from_wrc_info(file, wrc_command);
  end
  n = numel(order);
  t.axis_names = order;
  t.axes = cell(1, n);
  for k = 1:n
    t.axes{k} = double(data.axes.(order{k})(:));
  end
  t.outputs = struct();
  outputs = fieldnames(data.outputs);
  for k = 1:numel(outputs)
    t.outputs.(outputs{k}) = in_axis_order(data.outputs.(outputs{k}), n);
  end
  t.status = in_axis_order(data.status, n);
end

% The axes in dimension order when each dimension's length belongs to one axis only; {} when
% two axes have the same length (the shape cannot tell them apart).
function order = order_from_shape(reversed_shape, names, lengths)
  order = {};
  n = numel(names);
  shape = fliplr(reversed_shape);
  if n == 1
    order = names';
    return;
  end
  if numel(unique(lengths)) < n || numel(shape) ~= n
    return;
  end
  for k = 1:n
    order{k} = names{lengths == shape(k)};
  end
end

function order = order_from_wrc_info(file, wrc_command)
  [code, text] = system([wrc_command ' info --json "' file '"']);
  if code ~= 0
    error('wrc_read_table:order', ['%s: two axes have the same length, so the axis order ' ...
          'must come from the /axes attribute ''order'', which this Octave cannot read ' ...
          '(no h5readatt), and ''%s info --json'' failed: %s'], file, wrc_command, text);
  end
  info = jsondecode(text);
  order = cell(1, numel(info.axes));
  for k = 1:numel(info.axes)
    if iscell(info.axes)
      order{k} = info.axes{k}.name;
    else
      order{k} = info.axes(k).name;
    end
  end
end

% A stored N-D array with its dimensions back in axis order.
function a = in_axis_order(a, n)
  if n > 1
    a = permute(a, n:-1:1);
  end
end
